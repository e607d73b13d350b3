#include "track/track_steering.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "command/catalogue.hpp"
#include "geo/wgs84.hpp"
#include "session/image_commands.hpp"

namespace gimbald::track {

namespace session = gimbal::session;
namespace log = gimbal::log;

namespace {

double deg(double rad) {
    return rad * 180 / std::numbers::pi;
}
double rad(double deg) {
    return deg * std::numbers::pi / 180;
}

// The angle off the optical axis of an image coordinate (contract section 16's pinhole).
double off_axis_deg(double coordinate, double fov_deg) {
    return deg(std::atan(coordinate * std::tan(rad(fov_deg) / 2)));
}

}  // namespace

TrackSteering::TrackSteering(GimbalSession& session, gimbal::terrain::ElevationModel* terrain,
                             TrackSteeringOptions options)
    : session_(session),
      terrain_(terrain),
      options_(options),
      failed_log_(log::Level::warn, "track_steer_failed", "steering commands refused") {}

void TrackSteering::steer(double now, const std::optional<gimbal::track::GroundEstimate>& estimate,
                          double x, double y, bool seen) {
    if (now < next_s_) return;
    double period_s = 1 / options_.rate_hz;
    bool ok = false;
    if (estimate && !engaged_ && !velocity_known(*estimate) &&
        std::max(std::abs(x), std::abs(y)) < options_.edge) {
        next_s_ = now + period_s;  // the hand-over waits for the velocity
        return;
    }
    if (estimate) ok = point_at(*estimate, period_s);
    if ((!estimate || !ok) && !seen) {
        halt();  // nothing to go by: hold still rather than chase a guess
        next_s_ = now + period_s;
        return;
    }
    if (!estimate || !ok) {
        period_s = 1 / options_.rate_hz;
        ok = turn_towards(x, y);
    }
    engaged_ = engaged_ || ok;
    next_s_ = now + period_s;
}

bool TrackSteering::velocity_known(const gimbal::track::GroundEstimate& estimate) const {
    return estimate.fixes >= 2 && estimate.speed_sigma_mps < options_.velocity_sigma_mps;
}

bool TrackSteering::point_at(const gimbal::track::GroundEstimate& estimate, double& period_s) {
    const auto& capabilities = session_.capabilities();
    const auto view = capabilities.image();
    if (!view) return false;
    const bool leads = capabilities.holds_geopoint().has_value();
    period_s = 1 / (leads ? options_.leading_hz : options_.aimed_hz);
    gimbal::geo::GroundPoint target{estimate.position, 0, gimbal::geo::SurfaceKind::terrain};
    // Far from where the camera looks now: aim a bounded step from there towards the object
    // this time. Both are where they are now (the estimate is predicted to now, the axis
    // located with the latest pose); a box's image position, some frames old, is not.
    if (const auto axis = session::locate_point(*view, {0, 0}, terrain_)) {
        namespace geo = gimbal::geo;
        const geo::Vec3 eye = geo::lla_to_ecef(view->camera.position);
        const geo::Vec3 a = geo::lla_to_ecef(axis->point), b = geo::lla_to_ecef(estimate.position);
        const double cosine =
            geo::dot(a - eye, b - eye) / (geo::norm(a - eye) * geo::norm(b - eye));
        const double off_widths =
            deg(std::acos(std::clamp(cosine, -1.0, 1.0))) / view->camera.hfov_deg;
        const double step_widths = options_.max_slew_widths_s * period_s;
        if (off_widths > step_widths)
            target.point = geo::ecef_to_lla(a + (step_widths / off_widths) * (b - a));
    }
    auto request = session::point_request(capabilities, *view, target, false);
    if (!request) return false;
    // A gimbal that holds the location itself leads the object with its velocity.
    const auto* cmd = gimbal::command::find_command(request->value("cmd", std::string()));
    if (leads && cmd != nullptr && gimbal::command::find_param(*cmd, "vel_ned") != nullptr) {
        const bool known = velocity_known(estimate);
        (*request)["vel_ned"] = {known ? estimate.north_mps : 0.0, known ? estimate.east_mps : 0.0,
                                 0.0};
    }
    const bool ran = run(request);
    if (ran) turning_ = false;
    return ran;
}

bool TrackSteering::turn_towards(double x, double y) {
    const auto& capabilities = session_.capabilities();
    const auto view = capabilities.image();
    if (!view) return false;
    const auto bound = [this](double v) {
        return std::clamp(v, -options_.max_rate_dps, options_.max_rate_dps);
    };
    // y is down in the image, pitch up positive.
    const session::RateTarget rate{
        bound(-options_.rate_gain * off_axis_deg(y, view->camera.vfov_deg)),
        bound(options_.rate_gain * off_axis_deg(x, view->camera.hfov_deg))};
    const bool ran = run(capabilities.rate(rate));
    turning_ = turning_ || ran;
    return ran;
}

void TrackSteering::halt() {
    if (!turning_) return;
    turning_ = false;
    run(session_.capabilities().rate({0, 0}));
}

bool TrackSteering::run(const gimbal::command::Result<nlohmann::json>& request) {
    if (!request) return false;
    const std::string cmd = request->value("cmd", std::string());
    auto outcome = session_.execute(cmd, *request);
    if (outcome.error) {
        ++failed_;
        failed_log_.hit(outcome.error->message, {{"gimbal", session_.name()}, {"cmd", cmd}});
        return false;
    }
    ++sent_;
    return true;
}

}  // namespace gimbald::track
