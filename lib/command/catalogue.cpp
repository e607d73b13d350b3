#include "command/catalogue.hpp"

#include <array>
#include <numbers>

namespace gimbal::command {
namespace {

using P = ParamSpec;
using T = ParamType;

// Altitudes a command may name, metres (below the Dead Sea to well above any aircraft).
constexpr double min_alt = -2000;
constexpr double max_alt = 100000;
// OrionCmd targets are I16 scaled by 1000 (radians/s): the fastest rate, degrees/s.
constexpr double max_rate = 32.767 * 180.0 / std::numbers::pi;
// A velocity component on the wire: I16 scaled by 100, m/s.
constexpr double max_velocity = 327.67;

// ---- section 4.1: every gimbal ------------------------------------------------------------

constexpr std::array state_params{
    P{.name = "keys",
      .type = T::keys,
      .default_text = "all",
      .note = "`protocol`, `link` and `stale` always come"},
};

constexpr std::array subscribe_params{
    P{.name = "rate_hz", .min = 0.1, .max = 50, .unit = "Hz", .default_text = "10"},
    P{.name = "ttl_s", .min = 1, .max = 3600, .unit = "s", .default_text = "60"},
    P{.name = "events", .type = T::boolean, .default_text = "true"},
    P{.name = "keys", .type = T::keys, .default_text = "all", .note = "as for `state`"},
    P{.name = "changes",
      .type = T::boolean,
      .default_text = "false",
      .note = "a delta stream: merge patches between full STATEs"},
    P{.name = "full_every_s",
      .min = 1,
      .max = 3600,
      .unit = "s",
      .default_text = "10",
      .note = "with `changes`: a full STATE this often"},
};

// ---- sections 15 and 16: the ground and the image (gimbald answers them itself) -----------

constexpr std::array elevation_params{
    P{.name = "lat", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "lon", .required = true, .min = -180, .max = 180, .unit = "deg"},
};

// Pixel coordinates: the largest image a 16-bit size field describes.
constexpr double max_pixels = 65535;
constexpr std::array locate_params{
    P{.name = "x", .min = -1, .max = 1, .note = "left edge -1, right edge 1"},
    P{.name = "y", .min = -1, .max = 1, .note = "top edge -1, bottom edge 1"},
    P{.name = "px",
      .min = 0,
      .max = max_pixels,
      .note = "pixels from the left edge, up to the telemetry's `pixel_width`"},
    P{.name = "py",
      .min = 0,
      .max = max_pixels,
      .note = "pixels from the top edge, up to `pixel_height`"},
};

constexpr std::array project_params{
    P{.name = "lat", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "lon", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "alt", .required = true, .min = min_alt, .max = max_alt, .unit = "m"},
};

constexpr std::array point_params{
    locate_params[0],
    locate_params[1],
    locate_params[2],
    locate_params[3],
    P{.name = "stare",
      .type = T::boolean,
      .default_text = "false",
      .note = "stare at the point, where the gimbal's geopoint can"},
};

// ---- section 20: visual tracking (gimbald answers it with gimbal-track) -------------------

constexpr std::array track_params{
    locate_params[0],
    locate_params[1],
    locate_params[2],
    locate_params[3],
    P{.name = "x0", .min = -1, .max = 1, .note = "a box: left edge"},
    P{.name = "y0", .min = -1, .max = 1, .note = "a box: top edge"},
    P{.name = "x1", .min = -1, .max = 1, .note = "a box: right edge (> `x0`)"},
    P{.name = "y1", .min = -1, .max = 1, .note = "a box: bottom edge (> `y0`)"},
    P{.name = "px0", .min = 0, .max = max_pixels, .note = "a box in pixels: left edge"},
    P{.name = "py0", .min = 0, .max = max_pixels, .note = "a box in pixels: top edge"},
    P{.name = "px1", .min = 0, .max = max_pixels, .note = "a box in pixels: right edge"},
    P{.name = "py1", .min = 0, .max = max_pixels, .note = "a box in pixels: bottom edge"},
    P{.name = "size",
      .min = 0.01,
      .max = 0.5,
      .default_text = "0.08",
      .note = "a point's box: its side as a fraction of the image width"},
    P{.name = "steer",
      .type = T::boolean,
      .default_text = "the configuration's `tracking.steer`",
      .note = "keep the gimbal on the object"},
};

// ---- protocol commands --------------------------------------------------------------------

constexpr std::array<std::string_view, 3> alt_refs{"wgs84", "msl", "terrain"};
constexpr std::array geopoint_params{
    P{.name = "lat", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "lon", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "alt",
      .min = min_alt,
      .max = max_alt,
      .unit = "m",
      .default_text = "the terrain's height there",
      .note = "needed where no `terrain` covers the point"},
    P{.name = "alt_ref",
      .type = T::choice,
      .default_text = "wgs84",
      .choices = alt_refs,
      .note = "`msl` converts with the latest telemetry's geoid undulation; `terrain`: `alt` "
              "is height above the ground (default 0)"},
    P{.name = "vel_ned",
      .type = T::numbers,
      .min = -max_velocity,
      .max = max_velocity,
      .unit = "m/s",
      .default_text = "0 0 0",
      .count = 3},
    P{.name = "joystick_range_m",
      .type = T::integer,
      .min = 0,
      .max = 65535,
      .unit = "m",
      .default_text = "0"},
    P{.name = "stare", .type = T::boolean, .default_text = "false"},
    P{.name = "closure", .type = T::boolean, .default_text = "false"},
};

constexpr std::array<std::string_view, 2> path_alt_refs{"wgs84", "terrain"};
// A path point: `alt` may be left to the terrain (alt_ref, contract section 15).
constexpr std::array point_fields{
    P{.name = "lat", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "lon", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "alt", .min = min_alt, .max = max_alt, .unit = "m"},
};
constexpr std::array path_params{
    P{.name = "points",
      .type = T::points,
      .max = 15,
      .note = "altitudes above the WGS84 ellipsoid, `alt` optional where `terrain` covers the "
              "point; leave out with `down`",
      .fields = point_fields},
    P{.name = "alt_ref",
      .type = T::choice,
      .default_text = "wgs84",
      .choices = path_alt_refs,
      .note = "`terrain`: the points' `alt` is height above the ground (default 0)"},
    P{.name = "down",
      .type = T::boolean,
      .default_text = "false",
      .note = "point straight down, with no `points`"},
    P{.name = "along_step_deg", .min = 0, .max = 180, .unit = "deg", .default_text = "0"},
    P{.name = "cross_steps", .type = T::integer, .min = 0, .max = 15, .default_text = "0"},
    P{.name = "cross_ratio", .min = 0, .max = 2.55, .default_text = "0"},
};

constexpr std::array laser_params{
    P{.name = "index", .type = T::integer, .min = 0, .max = 1, .default_text = "0"},
    P{.name = "enable", .type = T::boolean, .required = true},
    P{.name = "arm", .type = T::boolean, .required = true},
    P{.name = "fire",
      .type = T::boolean,
      .required = true,
      .note = "needs `enable` and `arm` and laser.allow_fire"},
    P{.name = "on_ms",
      .type = T::integer,
      .min = 0,
      .max = 65535,
      .unit = "ms",
      .default_text = "0"},
    P{.name = "off_ms",
      .type = T::integer,
      .min = 0,
      .max = 65535,
      .unit = "ms",
      .default_text = "0"},
    P{.name = "prf_code", .type = T::integer, .min = 0, .max = 65535, .default_text = "0"},
    P{.name = "password", .type = T::text, .max = 15, .default_text = "\"\""},
    P{.name = "safety_bypass",
      .type = T::boolean,
      .default_text = "false",
      .note = "needs laser.allow_safety_bypass"},
};

constexpr std::array position_params{
    P{.name = "pan", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "tilt", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "stabilized", .type = T::boolean, .default_text = "false"},
    P{.name = "impulse_time_s", .min = 0, .max = 25.5, .unit = "s", .default_text = "0"},
};

constexpr std::array rate_params{
    P{.name = "pan", .required = true, .min = -max_rate, .max = max_rate, .unit = "deg/s"},
    P{.name = "tilt", .required = true, .min = -max_rate, .max = max_rate, .unit = "deg/s"},
    P{.name = "stabilized", .type = T::boolean, .default_text = "true"},
    P{.name = "impulse_time_s", .min = 0, .max = 25.5, .unit = "s", .default_text = "0"},
};

constexpr std::array<std::string_view, 7> mode_names{
    "disabled", "ffc_auto", "ffc_manual", "calibration", "scene", "track", "geo_rate"};
constexpr std::array mode_params{
    P{.name = "mode", .type = T::choice, .required = true, .choices = mode_names},
};

constexpr std::array stare_ack_params{
    P{.name = "system_time_ms",
      .type = T::integer,
      .min = 0,
      .max = 4294967295.0,
      .unit = "ms",
      .default_text = "the latest StareStart's"},
};

constexpr std::array<std::string_view, 3> retract_actions{"deploy", "retract", "disable"};
constexpr std::array retract_params{
    P{.name = "action", .type = T::choice, .required = true, .choices = retract_actions},
};

constexpr std::array camera_switch_params{
    P{.name = "index", .type = T::integer, .required = true, .min = 0, .max = 255},
};

constexpr std::array camera_zoom_params{
    P{.name = "zoom", .required = true, .min = -327.67, .max = 327.67, .note = "a ratio"},
    P{.name = "focus", .min = -3.2767, .max = 3.2767, .default_text = "-1"},
    P{.name = "index", .type = T::integer, .min = 0, .max = 255, .default_text = "0"},
};

constexpr std::array<std::string_view, 6> range_sources{"none",  "skylink",  "laser",
                                                        "other", "internal", "internal_dted"};
constexpr std::array range_params{
    P{.name = "range_m", .required = true, .min = 0, .max = 42949672.95, .unit = "m"},
    P{.name = "max_age_ms",
      .type = T::integer,
      .min = 0,
      .max = 65535,
      .unit = "ms",
      .default_text = "0"},
    P{.name = "source", .type = T::choice, .default_text = "none", .choices = range_sources},
};

constexpr std::array request_params{
    P{.name = "packet",
      .type = T::text,
      .required = true,
      .max = 64,
      .note = "a report or settings packet name (`crown_version`, `cameras`, `limits`, "
              "`network_settings`, ...) or `versions` for every version packet"},
};

constexpr std::array<std::string_view, 2> osds{"target", "uav"};
constexpr std::array<std::string_view, 4> out_formats{"out1", "out2", "out3", "out4"};
constexpr std::array output_params{
    P{.name = "osd", .type = T::choice, .required = true, .choices = osds},
    P{.name = "serial", .type = T::boolean, .required = true},
    P{.name = "network", .type = T::boolean, .required = true},
    P{.name = "format", .type = T::choice, .required = true, .choices = out_formats},
};

constexpr std::array adjust_params{
    P{.name = "yaw_deg", .min = -20, .max = 20, .unit = "deg", .note = "0.01 resolution"},
    P{.name = "pitch_deg", .min = -20, .max = 20, .unit = "deg", .note = "0.01 resolution"},
};

constexpr std::array vehicle_params{
    P{.name = "time",
      .type = T::text,
      .max = 40,
      .default_text = "now",
      .note = "ISO-8601 UTC, e.g. 2026-11-21T06:41:50.123Z"},
    P{.name = "roll", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "pitch", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "yaw", .required = true, .min = -180, .max = 360, .unit = "deg"},
    P{.name = "lat", .required = true, .min = -90, .max = 90, .unit = "deg"},
    P{.name = "lon", .required = true, .min = -180, .max = 180, .unit = "deg"},
    P{.name = "alt_msl", .required = true, .min = min_alt, .max = max_alt, .unit = "m"},
    P{.name = "vel_ned",
      .type = T::numbers,
      .min = -max_velocity,
      .max = max_velocity,
      .unit = "m/s",
      .count = 3,
      .note = "selects IN2"},
};

using C = CommandSpec;

constexpr std::array commands{
    C{.name = "ping",
      .scope = Scope::daemon,
      .access = Access::open,
      .needs_token = false,
      .summary = "Check that gimbald answers.",
      .reply = "`\"pong\": true`",
      .example = "{}"},
    C{.name = "version",
      .scope = Scope::daemon,
      .access = Access::open,
      .needs_token = false,
      .summary = "The daemon's version and the protocols it speaks.",
      .reply = "`\"version\": \"X.Y.Z\"`, `\"protocols\": [NAME, ...]`",
      .example = "{}"},
    C{.name = "list",
      .scope = Scope::daemon,
      .access = Access::open,
      .needs_token = false,
      .summary = "The configured gimbals with their protocol and link state.",
      .reply = "`\"gimbals\": [{\"name\",\"protocol\",\"link\":{\"type\",\"connected\"}}]`",
      .example = "{}"},
    C{.name = "state",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .needs_token = false,
      .summary = "The STATE object of one gimbal, whole or some of its keys.",
      .params = state_params,
      .reply = "`\"state\": STATE`",
      .example = "{}"},
    C{.name = "subscribe",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .summary = "Receive STATE and event datagrams until ttl_s passes without a renewal.",
      .params = subscribe_params,
      .reply = "echoes `rate_hz`, `ttl_s`, `events`, `keys` when given, and `changes`, "
               "`full_every_s` when `changes` is true",
      .example = "{}"},
    C{.name = "unsubscribe",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .summary = "Stop the STATE and event datagrams.",
      .reply = "`\"subscribed\": false`",
      .example = "{}"},
    C{.name = "elevation",
      .scope = Scope::daemon,
      .access = Access::observe,
      .summary = "The terrain's height at a point (needs `terrain`).",
      .params = elevation_params,
      .reply = "`\"alt\"` (above the ellipsoid), `\"alt_msl\"` (null with `\"geoid\": "
               "\"none\"`), `\"source\"` (the file); `unavailable` outside the terrain",
      .example = R"({"lat": 45.7, "lon": -121.5})"},
    C{.name = "locate",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .summary = "The ground point seen at an image position.",
      .params = locate_params,
      .rule = "`x`,`y` or `px`,`py`",
      .reply = "`\"lat\"`, `\"lon\"`, `\"alt\"`, `\"range_m\"`, `\"surface\"` "
               "(`terrain` or `ellipsoid`); `unavailable` when the ray misses the ground or "
               "no telemetry is known",
      .example = R"({"x": 0.5, "y": -0.25})"},
    C{.name = "project",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .summary = "Where a point appears in the current image (the inverse of locate).",
      .params = project_params,
      .reply = "`\"x\"`, `\"y\"` (null behind the camera), `\"visible\"` (in the image "
               "and not hidden by the terrain), and `\"px\"`, `\"py\"` when the image size "
               "is known",
      .example = R"({"lat": 45.69, "lon": -121.5, "alt": 400})"},
    C{.name = "point",
      .scope = Scope::every_gimbal,
      .summary = "Point the gimbal at the ground seen at an image position.",
      .params = point_params,
      .rule = "`x`,`y` or `px`,`py`",
      .reply = "the located point as `locate` gives it and `\"sent\"`; `unsupported` for a "
               "gimbal that cannot point at a location",
      .example = R"({"x": 0.5, "y": -0.3})"},
    C{.name = "klv",
      .scope = Scope::every_gimbal,
      .access = Access::observe,
      .summary = "The latest MISB ST 0601 KLV set of the gimbal's video, as bytes and decoded.",
      .reply = "`\"klv_hex\"` (the whole set, 16-byte key through checksum), `\"klv\"` "
               "(decoded, with `age_s`), `\"klv_source\"` (`stream` or `generated`); "
               "`unavailable` when there is none",
      .example = "{}"},
    C{.name = "track",
      .scope = Scope::every_gimbal,
      .summary = "Follow an object in the video: its box, its place on the ground, steering.",
      .params = track_params,
      .rule = "a point `x`,`y` (or `px`,`py`) with `size`, or a box `x0`,`y0`,`x1`,`y1` (or "
              "`px0`,`py0`,`px1`,`py1`)",
      .reply = "`\"track\"`: the track as STATE `track` shows it; `unavailable` without video, "
               "`video.tracking`, a running gimbal-track or image geometry",
      .example = R"({"x": 0.1, "y": -0.2})"},
    C{.name = "track_stop",
      .scope = Scope::every_gimbal,
      .summary = "End the visual track (event `track_end`, reason `stopped`).",
      .reply = "`\"stopped\"`: the id of the track ended, or null when none was running",
      .example = "{}"},
    C{.name = "geopoint",
      .summary = "Point at a geographic location.",
      .params = geopoint_params,
      .example = R"({"lat": 45.7, "lon": -121.5, "alt": 100})"},
    C{.name = "path",
      .summary = "Scan along a path of points, or point straight down.",
      .params = path_params,
      .rule = "`points` or `\"down\": true`, not both",
      .example = R"({"points": [{"lat": 45.7, "lon": -121.5, "alt": 100}]})"},
    C{.name = "laser",
      .access = Access::laser_when_firing,
      .summary = "Enable, arm or fire a laser (the laser role when it fires).",
      .params = laser_params,
      .example = R"({"enable": false, "arm": false, "fire": false})"},
    C{.name = "position",
      .summary = "Point at pan/tilt angles relative to the aircraft.",
      .params = position_params,
      .example = R"({"pan": 10, "tilt": -30})"},
    C{.name = "rate",
      .summary = "Move at pan/tilt rates.",
      .params = rate_params,
      .example = R"({"pan": 5, "tilt": 0})"},
    C{.name = "center",
      .summary = "Point forward and level: pan 0, tilt 0 relative to the aircraft.",
      .example = "{}"},
    C{.name = "mode",
      .summary = "Switch to a mode without targets.",
      .params = mode_params,
      .example = R"({"mode": "scene"})"},
    C{.name = "stare_ack",
      .summary = "Acknowledge a stare.",
      .params = stare_ack_params,
      .example = R"({"system_time_ms": 1000})"},
    C{.name = "retract",
      .summary = "Deploy or retract the gimbal.",
      .params = retract_params,
      .example = R"({"action": "deploy"})"},
    C{.name = "camera_switch",
      .summary = "Select the video camera.",
      .params = camera_switch_params,
      .example = R"({"index": 1})"},
    C{.name = "camera_zoom",
      .summary = "Set a camera's zoom ratio and focus.",
      .params = camera_zoom_params,
      .example = R"({"zoom": 2})"},
    C{.name = "range",
      .summary = "Give the gimbal a range to the target.",
      .params = range_params,
      .example = R"({"range_m": 1200})"},
    C{.name = "request",
      .summary = "Ask the gimbal to send a packet (a zero-length request).",
      .params = request_params,
      .example = R"({"packet": "cameras"})"},
    C{.name = "viewpro_output",
      .summary = "Set what the gimbal reports and where.",
      .params = output_params,
      .example = R"({"osd": "target", "serial": true, "network": false, "format": "out3"})"},
    C{.name = "viewpro_adjust",
      .summary = "Trim yaw and/or pitch in steps of at most one degree.",
      .params = adjust_params,
      .rule = "at least one of `yaw_deg` and `pitch_deg`",
      .example = R"({"yaw_deg": 1.5})"},
    C{.name = "vehicle",
      .summary = "Tell the gimbal the vehicle's attitude and position.",
      .params = vehicle_params,
      .example = R"({"roll": 0, "pitch": 0, "yaw": 90, "lat": 6.94, "lon": 79.88,)"
                 R"( "alt_msl": 300})"},
};

}  // namespace

std::span<const CommandSpec> catalogue() {
    return commands;
}

const CommandSpec* find_command(std::string_view name) {
    for (const auto& c : commands)
        if (c.name == name) return &c;
    return nullptr;
}

bool is_known_command(std::string_view name) {
    return find_command(name) != nullptr;
}

const ParamSpec* find_param(const CommandSpec& command, std::string_view name) {
    for (const auto& p : command.params)
        if (p.name == name) return &p;
    return nullptr;
}

std::string_view to_string(Scope scope) {
    switch (scope) {
        case Scope::daemon:
            return "daemon";
        case Scope::every_gimbal:
            return "every_gimbal";
        case Scope::protocol:
            return "protocol";
    }
    return "?";
}

std::string_view to_string(Access access) {
    switch (access) {
        case Access::open:
            return "open";
        case Access::observe:
            return "observe";
        case Access::control:
            return "control";
        case Access::laser_when_firing:
            return "laser_when_firing";
    }
    return "?";
}

std::string_view to_string(ParamType type) {
    switch (type) {
        case ParamType::number:
            return "number";
        case ParamType::integer:
            return "integer";
        case ParamType::boolean:
            return "boolean";
        case ParamType::text:
            return "text";
        case ParamType::choice:
            return "choice";
        case ParamType::numbers:
            return "numbers";
        case ParamType::points:
            return "points";
        case ParamType::keys:
            return "keys";
    }
    return "?";
}

}  // namespace gimbal::command
