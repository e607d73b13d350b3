#include "track/track_steering.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "command/catalogue.hpp"
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

TrackSteering::TrackSteering(GimbalSession& session, TrackSteeringOptions options)
    : session_(session),
      options_(options),
      failed_log_(log::Level::warn, "track_steer_failed", "steering commands refused") {}

void TrackSteering::steer(double now, const std::optional<gimbal::track::GroundEstimate>& estimate,
                          double x, double y) {
    if (now < next_s_) return;
    double period_s = 1 / options_.rate_hz;
    bool ok = false;
    if (estimate) ok = point_at(*estimate, period_s);
    if (!estimate || !ok) {
        period_s = 1 / options_.rate_hz;
        ok = turn_towards(x, y);
    }
    next_s_ = now + period_s;
}

bool TrackSteering::point_at(const gimbal::track::GroundEstimate& estimate, double& period_s) {
    const auto& capabilities = session_.capabilities();
    const auto view = capabilities.image();
    if (!view) return false;
    const gimbal::geo::GroundPoint target{estimate.position, 0, gimbal::geo::SurfaceKind::terrain};
    auto request = session::point_request(capabilities, *view, target, false);
    if (!request) return false;
    // A gimbal that holds the location itself leads the object with its velocity.
    const bool leads = capabilities.holds_geopoint().has_value();
    const auto* cmd = gimbal::command::find_command(request->value("cmd", std::string()));
    if (leads && cmd != nullptr && gimbal::command::find_param(*cmd, "vel_ned") != nullptr)
        (*request)["vel_ned"] = {estimate.north_mps, estimate.east_mps, 0.0};
    period_s = 1 / (leads ? options_.leading_hz : options_.aimed_hz);
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
