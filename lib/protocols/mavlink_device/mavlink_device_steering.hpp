// What gimbald holds a MAVLink gimbal device to (contract section 19): angles, rates, a
// geopoint (and its velocity) or a path, and the GIMBAL_DEVICE_SET_ATTITUDE that keeps it
// there, recomputed at every vehicle-feed tick (20 Hz) from the vehicle's fix. A device does
// not point at locations itself: gimbald aims it from the aircraft's position. Pure.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "geo/wgs84.hpp"
#include "mavlink/messages.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "sim/path_follower.hpp"

namespace gimbal::protocols {

// `position` (stabilized false): angles in the vehicle frame.
struct HoldAngles {
    double pan_deg = 0;   // from the vehicle's nose, right positive
    double tilt_deg = 0;  // from the horizon, up positive
};

// `position` stabilized: held in the earth frame, the yaw from north fixed when the command
// came (the vehicle's heading + pan), so the camera keeps its direction while the aircraft
// turns.
struct HoldHeading {
    double yaw_deg = 0;  // from north, right positive
    double tilt_deg = 0;
};

struct HoldRates {
    double pan_dps = 0;
    double tilt_dps = 0;
    std::optional<double> until_s;  // an impulse: the rates stop then
    bool earth = false;             // stabilized: the pan rate is from north (yaw lock)
};

struct HoldGeopoint {
    geo::Lla point;                   // above the ellipsoid
    std::array<double, 3> vel_ned{};  // m/s: the point moves
    double since_s = 0;               // when the point was where `point` says
    bool stare = false;               // emit stare_start once the device is on the point
    bool stared = false;              // ... which it has, for this command
};

// Where a held geopoint is at now_s (moved by its velocity).
geo::Lla geopoint_at(const HoldGeopoint& g, double now_s);

struct HoldPath {
    std::shared_ptr<sim::PathFollower> follower;  // shared: a held target is copyable
    double last_s = 0;
};

using Hold =
    std::variant<std::monostate, HoldAngles, HoldHeading, HoldRates, HoldGeopoint, HoldPath>;

// How a yaw from north reaches the device, from its GIMBAL_DEVICE_INFORMATION cap_flags.
enum class NorthYaw {
    // Neither capability (or no information yet): gimbald turns it into a yaw from the
    // vehicle's heading at every tick (YAW_IN_VEHICLE_FRAME).
    from_heading,
    // HAS_YAW_LOCK without SUPPORTS_YAW_IN_EARTH_FRAME (devices older than the frame
    // flags): YAW_LOCK and no frame flag, which common.xml keeps meaning "from north".
    yaw_lock,
    // SUPPORTS_YAW_IN_EARTH_FRAME: YAW_IN_EARTH_FRAME.
    earth_frame,
};
NorthYaw north_yaw_of(std::uint32_t cap_flags);

// The device's reported line of sight, for a path's on-target check.
struct Aim {
    geo::Quat camera_to_ned;
};

class MavlinkDeviceSteering {
  public:
    void hold(Hold h) { hold_ = std::move(h); }
    const Hold& held() const { return hold_; }
    Hold& held() { return hold_; }
    // How the device may be given yaw from north (north_yaw_of its cap_flags): a stare or a
    // stabilized hold then keeps while the aircraft turns between set-points.
    void set_north_yaw(NorthYaw how) { north_yaw_ = how; }

    // The set-attitude for now_s, or nullopt when nothing is held or the held target needs a
    // vehicle fix there is none of. `camera` is the camera's position above the ellipsoid.
    std::optional<mavlink::GimbalDeviceSetAttitude> command(
        const std::optional<vehicle::AircraftFix>& fix, const std::optional<geo::Lla>& camera,
        const std::optional<Aim>& aim, double now_s);
    // The stare a held path's step-stare began at the latest command(), once (stare_start).
    std::optional<sim::StareBegin> take_stare_begin() { return std::exchange(stare_began_, {}); }

  private:
    std::optional<mavlink::GimbalDeviceSetAttitude> heading(
        const HoldHeading& h, const std::optional<vehicle::AircraftFix>& fix) const;
    mavlink::GimbalDeviceSetAttitude rates(const HoldRates& r,
                                           const std::optional<vehicle::AircraftFix>& fix,
                                           double now_s) const;

    Hold hold_;
    std::optional<sim::StareBegin> stare_began_;
    NorthYaw north_yaw_ = NorthYaw::from_heading;
};

// The set-attitude that points pan/tilt in the vehicle frame (roll level): the `position`
// command's quaternion, per common.xml (w, x, y, z; Hamilton; yaw-pitch-roll).
mavlink::GimbalDeviceSetAttitude vehicle_frame_attitude(double pan_deg, double tilt_deg);

}  // namespace gimbal::protocols
