#include "sim/platform.hpp"

#include <cmath>

namespace gimbal::sim {

namespace {
constexpr double gravity = 9.80665;  // m/s^2
}

CirclePlatform::CirclePlatform(const CircleOptions& options)
    : options_(options),
      centre_ecef_(to_ecef(options.centre)),
      centre_ned_to_ecef_(ned_to_ecef(options.centre.lat, options.centre.lon)) {}

PlatformState CirclePlatform::at(double t) const {
    const double r = options_.radius_m > 0 ? options_.radius_m : 0.0;
    const double v = r > 0 ? options_.speed_mps : 0.0;
    const double turn = options_.clockwise ? 1.0 : -1.0;
    const double bearing = options_.start_bearing + turn * (r > 0 ? v / r : 0.0) * t;

    // Offset from the centre in the centre's tangent plane, then back to the circle's altitude
    // (the tangent plane drops below it by r^2 / 2R, 8 cm at 1 km).
    const Vec3 offset_ned{r * std::cos(bearing), r * std::sin(bearing), 0};
    Lla lla = to_lla(centre_ecef_ + centre_ned_to_ecef_ * offset_ned);
    lla.alt = options_.centre.alt;

    PlatformState s;
    s.lla = lla;
    s.ecef = to_ecef(lla);
    s.yaw = wrap_pi(bearing + turn * pi / 2);
    s.vel_ned = {v * std::cos(s.yaw), v * std::sin(s.yaw), 0};
    s.roll = r > 0 ? turn * std::atan(v * v / (gravity * r)) : 0.0;
    s.pitch = 0;
    s.attitude = quat_from_euler(s.roll, s.pitch, s.yaw);
    return s;
}

PlatformState platform_from_fix(const Lla& position, Vec3 vel_ned, double heading_if_slow) {
    PlatformState s;
    s.lla = position;
    s.ecef = to_ecef(position);
    s.vel_ned = vel_ned;
    const double ground_speed = std::hypot(vel_ned.x, vel_ned.y);
    s.yaw = ground_speed >= 1.0 ? std::atan2(vel_ned.y, vel_ned.x) : wrap_pi(heading_if_slow);
    s.attitude = quat_from_euler(0, 0, s.yaw);
    return s;
}

}  // namespace gimbal::sim
