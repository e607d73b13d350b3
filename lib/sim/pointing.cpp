#include "sim/pointing.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::sim {

Vec3 los_in_mount(PanTilt a) {
    const double ct = std::cos(a.tilt);
    return {ct * std::cos(a.pan), ct * std::sin(a.pan), -std::sin(a.tilt)};
}

PanTilt pan_tilt_for(Vec3 d) {
    const double horizontal = std::hypot(d.x, d.y);
    const double pan = horizontal > 1e-12 * norm(d) ? std::atan2(d.y, d.x) : 0.0;
    return {wrap_pi(pan), std::atan2(-d.z, horizontal)};
}

Mat3 mount_to_ecef(const Quat& mount_to_ned, double lat, double lon) {
    return ned_to_ecef(lat, lon) * dcm_from_quat(mount_to_ned);
}

GimbalAxes::GimbalAxes(AxisLimits limits, PanTilt start) : limits_(limits), angles_(start) {
    angles_.pan = wrap_pi(angles_.pan);
    angles_.tilt = clamp_tilt(angles_.tilt, true);
}

double GimbalAxes::clamp_tilt(double tilt, bool within_limits) const {
    if (!within_limits) return std::clamp(tilt, -pi, pi);
    return std::clamp(tilt, limits_.tilt_min, limits_.tilt_max);
}

void GimbalAxes::slew_toward(PanTilt target, double dt, bool within_limits) {
    if (dt <= 0) return;
    const double pan_error = wrap_pi(target.pan - angles_.pan);
    const double tilt_error = clamp_tilt(target.tilt, within_limits) - angles_.tilt;
    move_at(pan_error / dt, tilt_error / dt, dt, within_limits);
}

void GimbalAxes::move_at(double pan_rate, double tilt_rate, double dt, bool within_limits) {
    if (dt <= 0) return;
    pan_rate = std::clamp(pan_rate, -limits_.pan_rate_max, limits_.pan_rate_max);
    tilt_rate = std::clamp(tilt_rate, -limits_.tilt_rate_max, limits_.tilt_rate_max);
    const PanTilt before = angles_;
    angles_.pan = wrap_pi(angles_.pan + pan_rate * dt);
    // An axis left beyond a limit (after a no-limits command) comes back at its rate, no jump.
    const double tilt = angles_.tilt + tilt_rate * dt;
    angles_.tilt = within_limits ? std::clamp(tilt, std::min(limits_.tilt_min, angles_.tilt),
                                              std::max(limits_.tilt_max, angles_.tilt))
                                 : clamp_tilt(tilt, false);
    rates_ = {wrap_pi(angles_.pan - before.pan) / dt, (angles_.tilt - before.tilt) / dt};
}

}  // namespace gimbal::sim
