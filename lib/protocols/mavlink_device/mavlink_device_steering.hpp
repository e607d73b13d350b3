// What gimbald holds a MAVLink gimbal device to (contract section 19): angles, rates, a
// geopoint (and its velocity) or a path, and the GIMBAL_DEVICE_SET_ATTITUDE that keeps it
// there, recomputed at every vehicle-feed tick (20 Hz) from the vehicle's fix. A device does
// not point at locations itself: gimbald aims it from the aircraft's position. Pure.
#pragma once

#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "geo/wgs84.hpp"
#include "mavlink/messages.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "sim/path_follower.hpp"

namespace gimbal::protocols {

struct HoldAngles {
    double pan_deg = 0;   // from the vehicle's nose, right positive
    double tilt_deg = 0;  // from the horizon, up positive
};

struct HoldRates {
    double pan_dps = 0;
    double tilt_dps = 0;
    std::optional<double> until_s;  // an impulse: the rates stop then
};

struct HoldGeopoint {
    geo::Lla point;                   // above the ellipsoid
    std::array<double, 3> vel_ned{};  // m/s: the point moves
    double since_s = 0;               // when the point was where `point` says
};

struct HoldPath {
    std::shared_ptr<sim::PathFollower> follower;  // shared: a held target is copyable
    double last_s = 0;
};

using Hold = std::variant<std::monostate, HoldAngles, HoldRates, HoldGeopoint, HoldPath>;

// The device's reported line of sight, for a path's on-target check.
struct Aim {
    geo::Quat camera_to_ned;
};

class MavlinkDeviceSteering {
  public:
    void hold(Hold h) { hold_ = std::move(h); }
    const Hold& held() const { return hold_; }
    // Whether the device may be given yaw from north (GIMBAL_DEVICE_CAP_FLAGS_SUPPORTS_YAW_IN_
    // EARTH_FRAME): a stare then holds while the aircraft turns.
    void set_earth_frame(bool supported) { earth_frame_ = supported; }

    // The set-attitude for now_s, or nullopt when nothing is held or the held target needs a
    // vehicle fix there is none of. `camera` is the camera's position above the ellipsoid.
    std::optional<mavlink::GimbalDeviceSetAttitude> command(const std::optional<VehicleFix>& fix,
                                                            const std::optional<geo::Lla>& camera,
                                                            const std::optional<Aim>& aim,
                                                            double now_s);

  private:
    Hold hold_;
    bool earth_frame_ = false;
};

// The set-attitude that points pan/tilt in the vehicle frame (roll level): the `position`
// command's quaternion, per common.xml (w, x, y, z; Hamilton; yaw-pitch-roll).
mavlink::GimbalDeviceSetAttitude vehicle_frame_attitude(double pan_deg, double tilt_deg);

}  // namespace gimbal::protocols
