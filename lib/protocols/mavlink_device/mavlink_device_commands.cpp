#include "protocols/mavlink_device/mavlink_device_commands.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "command/params.hpp"

namespace gimbal::protocols {

namespace {

namespace code = command::code;
using command::Params;
using nlohmann::json;

// The catalogue's ranges (lib/command/catalogue.cpp).
constexpr double min_alt_m = -2000;
constexpr double max_alt_m = 100000;
constexpr double max_rate_dps = 32.767 * 180.0 / std::numbers::pi;
constexpr double max_velocity = 327.67;
constexpr std::size_t max_path_points = 15;
constexpr double deg = std::numbers::pi / 180.0;

command::Error no_fix(std::string_view cmd) {
    return {code::unavailable, std::string(cmd) +
                                   " needs the vehicle's position and attitude: gimbald aims a "
                                   "MAVLink device itself (configure `vehicle`)"};
}

command::Result<Hold> position(Params& p) {
    const auto pan = p.number("pan", -180.0, 180.0, true);
    const auto tilt = p.number("tilt", -180.0, 180.0, true);
    (void)p.boolean_or("stabilized", false);  // the device keeps roll and pitch level anyway
    (void)p.number_or("impulse_time_s", 0.0, 25.5, 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    return Hold{HoldAngles{*pan, *tilt}};
}

command::Result<Hold> rate(Params& p, const DeviceCommandContext& ctx) {
    const auto pan = p.number("pan", -max_rate_dps, max_rate_dps, true);
    const auto tilt = p.number("tilt", -max_rate_dps, max_rate_dps, true);
    (void)p.boolean_or("stabilized", true);
    const double impulse = p.number_or("impulse_time_s", 0.0, 25.5, 0.0);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    HoldRates r{*pan, *tilt, std::nullopt};
    if (impulse > 0) r.until_s = ctx.now_s + impulse;
    return Hold{r};
}

command::Result<Hold> geopoint(Params& p, const DeviceCommandContext& ctx) {
    const auto lat = p.number("lat", -90.0, 90.0, true);
    const auto lon = p.number("lon", -180.0, 180.0, true);
    const auto alt = p.number("alt", min_alt_m, max_alt_m, true);
    static constexpr std::array<std::string_view, 3> refs{"wgs84", "msl", "terrain"};
    const auto ref = p.choice("alt_ref", refs, false).value_or("wgs84");
    const auto vel = p.numbers("vel_ned", 3, -max_velocity, max_velocity, false);
    // The Orion's own geopoint options: a device has no stare or closure of its own.
    (void)p.integer_or("joystick_range_m", 0, 65535, 0);
    (void)p.boolean_or("stare", false);
    (void)p.boolean_or("closure", false);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (ref == "terrain")
        return command::Error{code::unavailable,
                              "alt_ref 'terrain' needs gimbald's terrain section"};
    if (!ctx.has_vehicle_fix) return no_fix("geopoint");
    HoldGeopoint g;
    g.point = {*lat, *lon, ref == "msl" ? *alt + ctx.geoid_undulation_m : *alt};
    if (vel) g.vel_ned = {(*vel)[0], (*vel)[1], (*vel)[2]};
    g.since_s = ctx.now_s;
    return Hold{g};
}

command::Result<Hold> path(Params& p, const DeviceCommandContext& ctx) {
    const json* points = p.raw("points");
    const bool down = p.boolean_or("down", false);
    const double along = p.number_or("along_step_deg", 0.0, 180.0, 0.0);
    const auto cross_steps = p.integer_or("cross_steps", 0, 15, 0);
    const double cross_ratio = p.number_or("cross_ratio", 0.0, 2.55, 0.0);
    static constexpr std::array<std::string_view, 2> refs{"wgs84", "terrain"};
    const auto ref = p.choice("alt_ref", refs, false).value_or("wgs84");
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (ref == "terrain")
        return command::Error{code::unavailable,
                              "alt_ref 'terrain' needs gimbald's terrain section"};
    if (down) {
        if (points) return command::Error{code::bad_request, "'down': true takes no 'points'"};
        return Hold{HoldAngles{0, -90}};
    }
    if (!points)
        return command::Error{code::bad_request, "missing parameter 'points' (or 'down': true)"};
    if (!points->is_array() || points->empty())
        return command::Error{code::bad_request, "'points' must be an array of 1 to 15 points"};
    if (points->size() > max_path_points)
        return command::Error{code::out_of_range, "'points' must hold 1 to 15 points"};
    std::vector<geo::Vec3> ecef;
    for (std::size_t i = 0; i < points->size(); ++i) {
        const auto& item = (*points)[i];
        const std::string where = "points[" + std::to_string(i) + "]";
        if (!item.is_object())
            return command::Error{code::bad_request, where + " must be {\"lat\",\"lon\",\"alt\"}"};
        Params point(item);
        const auto lat = point.number("lat", -90.0, 90.0, true);
        const auto lon = point.number("lon", -180.0, 180.0, true);
        const auto alt = point.number("alt", min_alt_m, max_alt_m, true);
        point.reject_unknown();
        if (!point.ok())
            return command::Error{point.error().code, where + ": " + point.error().message};
        ecef.push_back(geo::lla_to_ecef({*lat, *lon, *alt}));
    }
    if (!ctx.has_vehicle_fix) return no_fix("path");
    // The Orion's along/cross-step semantics (sim::PathFollower): the look point sweeps the
    // path, or steps along it by the slant range times the step angle and stares.
    sim::StepStare step;
    step.along_step = along * deg;
    step.cross_steps = static_cast<unsigned>(cross_steps);
    step.cross_ratio = cross_ratio;
    HoldPath h;
    h.follower = std::make_shared<sim::PathFollower>(std::move(ecef), step, sim::PathOptions{});
    h.last_s = ctx.now_s;
    return Hold{h};
}

}  // namespace

bool is_device_command(std::string_view cmd) {
    return cmd == "position" || cmd == "rate" || cmd == "geopoint" || cmd == "path";
}

command::Result<Hold> plan_device_command(std::string_view cmd, const json& request,
                                          const DeviceCommandContext& context) {
    Params p(request);
    if (cmd == "position") return position(p);
    if (cmd == "rate") return rate(p, context);
    if (cmd == "geopoint") return geopoint(p, context);
    if (cmd == "path") return path(p, context);
    return command::Error{code::unsupported,
                          "'" + std::string(cmd) + "' is not a MAVLink gimbal device command"};
}

}  // namespace gimbal::protocols
