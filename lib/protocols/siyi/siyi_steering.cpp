#include "protocols/siyi/siyi_steering.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "session/capabilities.hpp"

namespace gimbal::protocols {

namespace {

geo::Lla moved(const geo::Lla& p, const std::array<double, 3>& v_ned, double dt) {
    if (dt == 0 || (v_ned[0] == 0 && v_ned[1] == 0 && v_ned[2] == 0)) return p;
    const geo::Vec3 d = geo::ned_to_ecef(geo::Vec3{v_ned[0] * dt, v_ned[1] * dt, v_ned[2] * dt}, p);
    return geo::ecef_to_lla(geo::lla_to_ecef(p) + d);
}

std::int8_t speed(double dps, double max_dps) {
    if (!std::isfinite(dps) || max_dps <= 0) return 0;
    return static_cast<std::int8_t>(std::clamp(std::round(dps / max_dps * 100.0), -100.0, 100.0));
}

}  // namespace

siyi::SetGimbalAttitude siyi_angles(double pan_deg, double tilt_deg) {
    return siyi::SetGimbalAttitude{session::wrap180(-pan_deg), tilt_deg};
}

siyi::GimbalRotation siyi_speeds(double pan_dps, double tilt_dps, const siyi::ModelInfo& model) {
    return siyi::GimbalRotation{speed(pan_dps, model.max_rate_dps),
                                speed(tilt_dps, model.max_rate_dps)};
}

geo::Lla siyi_geopoint_at(const SiyiHoldGeopoint& g, double now_s) {
    return moved(g.point, g.vel_ned, now_s - g.since_s);
}

std::optional<siyi::ToGimbal> SiyiSteering::expire(double now_s) {
    const auto* r = std::get_if<SiyiHoldRates>(&hold_);
    if (!r || now_s < r->until_s) return std::nullopt;
    hold_ = std::monostate{};  // the impulse is over: stop, once
    return siyi::GimbalRotation{0, 0};
}

std::optional<siyi::ToGimbal> SiyiSteering::command(const std::optional<vehicle::AircraftFix>& fix,
                                                    const std::optional<geo::Lla>& camera,
                                                    const std::optional<geo::Quat>& line_of_sight,
                                                    double now_s) {
    if (std::holds_alternative<SiyiHoldRates>(hold_)) return expire(now_s);
    if (!fix) return std::nullopt;
    if (const auto* h = std::get_if<SiyiHoldHeading>(&hold_))
        return siyi_angles(session::wrap180(h->yaw_deg - fix->yaw_deg), h->tilt_deg);
    if (!camera) return std::nullopt;

    geo::Lla target;
    if (const auto* g = std::get_if<SiyiHoldGeopoint>(&hold_)) {
        target = siyi_geopoint_at(*g, now_s);
    } else if (auto* p = std::get_if<SiyiHoldPath>(&hold_)) {
        const geo::Vec3 at = geo::lla_to_ecef(*camera);
        double error = std::numbers::pi;
        if (line_of_sight) {
            const geo::Vec3 los =
                geo::ned_to_ecef(geo::rotate(*line_of_sight, geo::Vec3{1, 0, 0}), *camera);
            error = sim::angle_between(los, p->follower->look_point() - at);
        }
        // A stare ends by its own timeout: SIYI has no stare of its own to acknowledge.
        (void)p->follower->step(std::max(0.0, now_s - p->last_s), at, error);
        p->last_s = now_s;
        target = geo::ecef_to_lla(p->follower->look_point());
    } else {
        return std::nullopt;
    }
    const auto look = geo::look_angles(*camera, target);
    if (!(look.range_m > 0)) return std::nullopt;
    return siyi_angles(session::wrap180(look.azimuth_deg - fix->yaw_deg), look.elevation_deg);
}

}  // namespace gimbal::protocols
