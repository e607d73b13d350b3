#include "protocols/viewpro/viewpro_commands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

#include "command/params.hpp"
#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/time.hpp"

namespace gimbal::command {
namespace {

namespace v = gimbal::viewpro;

void add(Plan& plan, std::string_view frame, std::span<const std::uint8_t> bytes) {
    WirePacket w;
    w.frame.assign(bytes.begin(), bytes.end());
    w.sent = {{"frame", frame}, {"len", bytes.size()}};
    plan.packets.push_back(std::move(w));
}

void output(JsonParams& p, Plan& plan) {
    const auto osd = p.choice("osd", true);
    const auto serial = p.boolean("serial", true);
    const auto network = p.boolean("network", true);
    const auto format = p.choice("format", true);
    if (!p.ok()) return;
    v::Mode mode;
    mode.osd = *v::parse_osd(*osd);
    mode.serial = *serial;
    mode.network = *network;
    mode.format = *v::parse_out_format(*format);
    add(plan, "mode", v::encode_mode(mode));
}

// Splits a shift of `deg` into steps of at most 1.00 degree (|XX| <= 100), as the ICD's
// examples do: 5.5 degrees -> 100 x5, then 50.
std::vector<std::int8_t> shift_steps(double deg) {
    long remaining = std::lround(deg * 100.0);
    std::vector<std::int8_t> steps;
    while (remaining != 0) {
        const long step = std::clamp<long>(remaining, -v::max_shift_step, v::max_shift_step);
        steps.push_back(static_cast<std::int8_t>(step));
        remaining -= step;
    }
    return steps;
}

void adjust(JsonParams& p, Plan& plan) {
    const auto yaw = p.number("yaw_deg", false);
    const auto pitch = p.number("pitch_deg", false);
    p.reject_unknown();  // a misspelt key explains a missing shift better than the rule below
    if (!p.ok()) return;
    if (!yaw && !pitch) return p.fail(code::bad_request, "give 'yaw_deg' and/or 'pitch_deg'");
    for (const auto step : shift_steps(yaw.value_or(0.0)))
        add(plan, "yaw_shift", v::encode_yaw_shift(step));
    for (const auto step : shift_steps(pitch.value_or(0.0)))
        add(plan, "pitch_shift", v::encode_pitch_shift(step));
    plan.result["steps"] = plan.packets.size();
}

void vehicle(JsonParams& p, const ViewproContext& ctx, Plan& plan) {
    const auto time = p.text("time", false);
    const auto roll = p.number("roll", true);
    const auto pitch = p.number("pitch", true);
    const auto yaw = p.number("yaw", true);
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    const auto alt = p.number("alt_msl", true);
    const auto vel = p.numbers("vel_ned", false);
    if (!p.ok()) return;
    v::VehicleInput in;
    if (time) {
        const auto parsed = v::parse_iso8601(*time);
        if (!parsed)
            return p.fail(code::bad_request,
                          "'time' must be an ISO-8601 UTC time such as 2026-11-21T06:41:50Z");
        in.time = *parsed;
    } else {
        in.time = v::from_unix_seconds(ctx.unix_time_s);
    }
    in.roll_deg = *roll;
    in.pitch_deg = *pitch;
    in.yaw_deg = *yaw;
    in.lat_deg = *lat;
    in.lon_deg = *lon;
    in.alt_msl_m = *alt;
    if (vel) in.vel_ned_mps = std::array<double, 3>{(*vel)[0], (*vel)[1], (*vel)[2]};
    const auto bytes = v::encode_vehicle(in);
    add(plan, vel ? "in2" : "in1", bytes);
}

}  // namespace

bool is_viewpro_command(std::string_view cmd) {
    return cmd == "viewpro_output" || cmd == "viewpro_adjust" || cmd == "vehicle";
}

std::optional<Error> plan_viewpro(std::string_view cmd, const nlohmann::json& request,
                                  const ViewproContext& context, Plan& plan) {
    JsonParams params(request, cmd);
    if (cmd == "viewpro_output")
        output(params, plan);
    else if (cmd == "viewpro_adjust")
        adjust(params, plan);
    else if (cmd == "vehicle")
        vehicle(params, context, plan);
    else
        return Error{code::unknown_cmd, "unknown command"};
    params.reject_unknown();
    if (!params.ok()) {
        plan = Plan{};
        return params.error();
    }
    return std::nullopt;
}

}  // namespace gimbal::command
