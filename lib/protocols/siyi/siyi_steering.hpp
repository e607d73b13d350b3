// What gimbald holds a SIYI camera to between commands, and the SIYI message that keeps it
// there at every vehicle-feed tick (20 Hz). A SIYI camera takes angles relative to the
// aircraft's nose and speeds; it does not point at locations itself: gimbald aims it from the
// aircraft's position, as it aims a MAVLink gimbal device (docs/architecture.md). Angles in
// gimbald's frame (pan right positive); the messages in SIYI's (docs/siyi.md). Pure.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <variant>

#include "geo/attitude.hpp"
#include "geo/wgs84.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/codec/models.hpp"
#include "sim/frames.hpp"
#include "sim/path_follower.hpp"
#include "vehicle/aircraft_fix.hpp"

namespace gimbal::protocols {

// `position` stabilized: the yaw from north fixed when the command came, re-sent as a pan
// from the nose while the aircraft turns.
struct SiyiHoldHeading {
    double yaw_deg = 0;  // from north, right positive
    double tilt_deg = 0;
};

// `rate` with an impulse: the speeds stop at until_s.
struct SiyiHoldRates {
    double until_s = 0;
};

struct SiyiHoldGeopoint {
    geo::Lla point;                   // above the ellipsoid
    std::array<double, 3> vel_ned{};  // m/s: the point moves
    double since_s = 0;               // when the point was where `point` says
    bool stare = false;               // emit stare_start once the camera is on the point
    bool stared = false;              // ... which it has, for this command
};

struct SiyiHoldPath {
    std::shared_ptr<sim::PathFollower> follower;  // shared: a held target is copyable
    double last_s = 0;
};

using SiyiHold =
    std::variant<std::monostate, SiyiHoldHeading, SiyiHoldRates, SiyiHoldGeopoint, SiyiHoldPath>;

// The 0x0E absolute angles for a pan and tilt in gimbald's frame (SIYI yaw = -pan).
siyi::SetGimbalAttitude siyi_angles(double pan_deg, double tilt_deg);
// The 0x07 speeds for pan and tilt rates: 100 is the model's top rate; right and up positive.
siyi::GimbalRotation siyi_speeds(double pan_dps, double tilt_dps, const siyi::ModelInfo& model);
// Where a held geopoint is at now_s (moved by its velocity).
geo::Lla siyi_geopoint_at(const SiyiHoldGeopoint& g, double now_s);

class SiyiSteering {
  public:
    void hold(SiyiHold h) { hold_ = std::move(h); }
    const SiyiHold& held() const { return hold_; }
    SiyiHold& held() { return hold_; }

    // The stop of a rate's impulse once it is over (0x07 0 0), else nullopt: due even without
    // a vehicle feed (the session asks at every frame from the camera).
    std::optional<siyi::ToGimbal> expire(double now_s);
    // The message for now_s (expire's included), or nullopt when nothing is due (nothing held, an
    // angle hold without the vehicle's fix). `camera`: the camera's position above the ellipsoid;
    // `line_of_sight`: the camera's, relative to NED, for a path's on-target check.
    std::optional<siyi::ToGimbal> command(const std::optional<vehicle::AircraftFix>& fix,
                                          const std::optional<geo::Lla>& camera,
                                          const std::optional<geo::Quat>& line_of_sight,
                                          double now_s);

  private:
    SiyiHold hold_;
};

}  // namespace gimbal::protocols
