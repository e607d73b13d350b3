#include "protocols/siyi/siyi_commands.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "command/geopoint_request.hpp"
#include "command/params.hpp"
#include "command/path_request.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

namespace {

namespace code = command::code;
using command::JsonParams;
using nlohmann::json;

constexpr double deg = std::numbers::pi / 180.0;

std::shared_ptr<const SiyiHold> holding(SiyiHold hold) {
    return std::make_shared<const SiyiHold>(std::move(hold));
}

command::Error no_fix(std::string_view cmd) {
    return {code::unavailable, std::string(cmd) +
                                   " needs the vehicle's position and attitude: gimbald aims a "
                                   "SIYI camera itself (configure `vehicle`)"};
}

// Unstabilized: 0x0E once (the camera holds angles from the nose). Stabilized: a yaw from
// north, re-sent from the aircraft's heading at every tick.
command::Result<SiyiPlan> position(JsonParams& p, const SiyiCommandContext& ctx) {
    const auto pan = p.number("pan", true);
    const auto tilt = p.number("tilt", true);
    const bool stabilized = p.boolean_or("stabilized", false);
    (void)p.number_or("impulse_time_s", 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    SiyiPlan plan;
    if (!stabilized) {
        plan.send.emplace_back(siyi_angles(*pan, *tilt));
        plan.hold = holding(SiyiHold{});
        return plan;
    }
    if (!ctx.vehicle_yaw_deg)
        return command::Error{code::unavailable,
                              "position with stabilized true needs the vehicle's heading (the "
                              "pan is held from north): configure `vehicle`, or send "
                              "stabilized false"};
    plan.send.emplace_back(siyi_angles(*pan, *tilt));
    plan.hold = holding(SiyiHoldHeading{session::wrap180(*ctx.vehicle_yaw_deg + *pan), *tilt});
    return plan;
}

// 0x08 one-key centring: the camera returns to its nose-forward, level home by itself; any
// held target is let go so that the next tick does not turn it away again.
command::Result<SiyiPlan> center(JsonParams& p) {
    p.reject_unknown();
    if (!p.ok()) return p.error();
    SiyiPlan plan;
    plan.send.emplace_back(siyi::Center{siyi::CenterPosition::one_key_center});
    plan.hold = holding(SiyiHold{});
    return plan;
}

// 0x07 speeds; the camera keeps turning until told 0 0. `stabilized` changes nothing: its
// pitch is held in the earth frame in every mode, its yaw as its motion mode says.
command::Result<SiyiPlan> rate(JsonParams& p, const SiyiCommandContext& ctx) {
    const auto pan = p.number("pan", true);
    const auto tilt = p.number("tilt", true);
    (void)p.boolean_or("stabilized", true);
    const double impulse = p.number_or("impulse_time_s", 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    SiyiPlan plan;
    plan.send.emplace_back(siyi_speeds(*pan, *tilt, *ctx.model));
    plan.hold = holding(impulse > 0 ? SiyiHold{SiyiHoldRates{ctx.now_s + impulse}} : SiyiHold{});
    return plan;
}

// 0x0F absolute zoom, one decimal, within the model's range. SIYI focuses by itself.
command::Result<SiyiPlan> camera_zoom(JsonParams& p, const SiyiCommandContext& ctx) {
    const auto zoom = p.number("zoom", true);
    const auto focus = p.number("focus", false);
    const auto index = p.integer_or("index", 0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (index != 0)
        return command::Error{code::bad_request, "index must be 0: a SIYI camera zooms one camera"};
    if (focus && *focus != -1.0)
        return command::Error{code::unsupported,
                              "a SIYI camera focuses by itself: leave focus out or give -1"};
    // The model's range, beyond the catalogue's (which is the widest of every protocol).
    const double max = ctx.model->zoom_max;
    if (*zoom < 1.0 || *zoom > max) {
        char range[64];
        std::snprintf(range, sizeof range, "between 1 and %.1f", max);
        return command::Error{code::out_of_range, "the zoom ratio must be " + std::string(range) +
                                                      " for the " + std::string(ctx.model->name)};
    }
    SiyiPlan plan;
    plan.send.emplace_back(siyi::AbsoluteZoom{std::round(*zoom * 10.0) / 10.0});
    return plan;
}

command::Result<SiyiPlan> geopoint(JsonParams& p, const SiyiCommandContext& ctx) {
    auto read = command::read_aimed_geopoint(p, ctx.geoid_undulation_m, "a SIYI camera");
    if (!read) return read.error();
    if (!ctx.has_vehicle_fix) return no_fix("geopoint");
    SiyiHoldGeopoint g;
    g.point = read->point;
    g.vel_ned = read->vel_ned;
    g.since_s = ctx.now_s;
    // stare: gimbald watches the camera's line of sight (siyi_stare.hpp).
    g.stare = read->stare;
    SiyiPlan plan;
    plan.hold = holding(g);
    return plan;
}

command::Result<SiyiPlan> path(JsonParams& p, const SiyiCommandContext& ctx) {
    auto read = command::read_path_request(p);
    if (!read) return read.error();
    SiyiPlan plan;
    if (read->down) {
        plan.send.emplace_back(siyi_angles(0, -90));
        plan.hold = holding(SiyiHold{});
        return plan;
    }
    if (!ctx.has_vehicle_fix) return no_fix("path");
    sim::StepStare step;
    step.along_step = read->along_step_deg * deg;
    step.cross_steps = read->cross_steps;
    step.cross_ratio = read->cross_ratio;
    SiyiHoldPath h;
    h.follower =
        std::make_shared<sim::PathFollower>(std::move(read->ecef), step, sim::PathOptions{});
    h.last_s = ctx.now_s;
    plan.hold = holding(h);
    return plan;
}

}  // namespace

bool is_siyi_command(std::string_view cmd) {
    return cmd == "position" || cmd == "center" || cmd == "rate" || cmd == "camera_zoom" ||
           cmd == "geopoint" || cmd == "path";
}

command::Result<SiyiPlan> plan_siyi_command(std::string_view cmd, const json& request,
                                            const SiyiCommandContext& context) {
    JsonParams p(request, cmd);
    if (cmd == "position") return position(p, context);
    if (cmd == "center") return center(p);
    if (cmd == "rate") return rate(p, context);
    if (cmd == "camera_zoom") return camera_zoom(p, context);
    if (cmd == "geopoint") return geopoint(p, context);
    if (cmd == "path") return path(p, context);
    return command::Error{code::unsupported,
                          "'" + std::string(cmd) + "' is not a SIYI camera command"};
}

}  // namespace gimbal::protocols
