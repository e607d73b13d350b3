#include "protocols/mavlink_device/mavlink_device_commands.hpp"

#include <array>
#include <cmath>
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

command::Error no_fix(std::string_view cmd) {
    return {code::unavailable, std::string(cmd) +
                                   " needs the vehicle's position and attitude: gimbald aims a "
                                   "MAVLink device itself (configure `vehicle`)"};
}

// The Orion's meaning of `stabilized` (contract section 4): held in the earth frame. Roll
// and pitch are levelled by the device either way.
command::Result<Hold> position(JsonParams& p, const DeviceCommandContext& ctx) {
    const auto pan = p.number("pan", true);
    const auto tilt = p.number("tilt", true);
    const bool stabilized = p.boolean_or("stabilized", false);
    (void)p.number_or("impulse_time_s", 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (!stabilized) return Hold{HoldAngles{*pan, *tilt}};
    // The pan becomes a yaw from north now: it needs the aircraft's heading.
    if (!ctx.has_vehicle_fix)
        return command::Error{code::unavailable,
                              "position with stabilized true needs the vehicle's heading (the "
                              "pan is held from north): configure `vehicle`, or send "
                              "stabilized false"};
    return Hold{HoldHeading{session::wrap180(ctx.vehicle_heading_deg + *pan), *tilt}};
}

command::Result<Hold> rate(JsonParams& p, const DeviceCommandContext& ctx) {
    const auto pan = p.number("pan", true);
    const auto tilt = p.number("tilt", true);
    const bool stabilized = p.boolean_or("stabilized", true);
    const double impulse = p.number_or("impulse_time_s", 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    HoldRates r{*pan, *tilt, std::nullopt, stabilized};
    if (impulse > 0) r.until_s = ctx.now_s + impulse;
    return Hold{r};
}

command::Result<Hold> geopoint(JsonParams& p, const DeviceCommandContext& ctx) {
    // stare: gimbald watches the device's line of sight (mavlink_device_stare.hpp).
    auto read = command::read_aimed_geopoint(p, ctx.geoid_undulation_m, "a MAVLink gimbal device");
    if (!read) return read.error();
    if (!ctx.has_vehicle_fix) return no_fix("geopoint");
    HoldGeopoint g;
    g.point = read->point;
    g.vel_ned = read->vel_ned;
    g.since_s = ctx.now_s;
    g.stare = read->stare;
    return Hold{g};
}

command::Result<Hold> path(JsonParams& p, const DeviceCommandContext& ctx) {
    auto read = command::read_path_request(p);
    if (!read) return read.error();
    if (read->down) return Hold{HoldAngles{0, -90}};
    if (!ctx.has_vehicle_fix) return no_fix("path");
    // The Orion's along/cross-step semantics (sim::PathFollower): the look point sweeps the
    // path, or steps along it by the slant range times the step angle and stares.
    sim::StepStare step;
    step.along_step = read->along_step_deg * deg;
    step.cross_steps = read->cross_steps;
    step.cross_ratio = read->cross_ratio;
    HoldPath h;
    h.follower =
        std::make_shared<sim::PathFollower>(std::move(read->ecef), step, sim::PathOptions{});
    h.last_s = ctx.now_s;
    return Hold{h};
}

}  // namespace

bool is_device_command(std::string_view cmd) {
    return cmd == "position" || cmd == "center" || cmd == "rate" || cmd == "geopoint" ||
           cmd == "path" || cmd == "stare_ack";
}

command::Result<Hold> plan_device_command(std::string_view cmd, const json& request,
                                          const DeviceCommandContext& context) {
    JsonParams p(request, cmd);
    if (cmd == "position") return position(p, context);
    if (cmd == "center") {  // forward and level in the aircraft's frame, held
        p.reject_unknown();
        if (!p.ok()) return p.error();
        return Hold{HoldAngles{0.0, 0.0}};
    }
    if (cmd == "rate") return rate(p, context);
    if (cmd == "geopoint") return geopoint(p, context);
    if (cmd == "path") return path(p, context);
    return command::Error{code::unsupported,
                          "'" + std::string(cmd) + "' is not a MAVLink gimbal device command"};
}

}  // namespace gimbal::protocols
