#include "session/ground_altitude.hpp"

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "command/catalogue.hpp"
#include "command/params.hpp"

namespace gimbal::session {

namespace {

using command::Error;
using nlohmann::json;
namespace code = command::code;

// What a point object is read against: the catalogue's geopoint parameters, or the fields
// of a path's points.
std::span<const command::ParamSpec> specs_of(std::string_view cmd, std::string_view structured) {
    const command::CommandSpec* spec = command::find_command(cmd);
    if (!spec) return {};
    if (structured.empty()) return spec->params;
    for (const command::ParamSpec& param : spec->params)
        if (param.name == structured) return param.fields;
    return {};
}

bool present(const json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && !it->is_null();
}

// The alt_ref of a request (nullopt when absent), refused when not one of its command's.
command::Result<std::optional<std::string>> alt_ref(const json& request, std::string_view cmd) {
    command::JsonParams p(request, cmd);
    auto ref = p.choice("alt_ref", false);
    if (!p.ok()) return p.error();
    return ref;
}

// The ellipsoid altitude for one point object: the terrain's height there plus the height
// above ground when `above_ground`, else the terrain's height. `where` prefixes messages.
command::Result<double> ground_altitude(const json& point,
                                        std::span<const command::ParamSpec> specs,
                                        bool above_ground, geo::Surface* terrain,
                                        const std::string& where) {
    command::JsonParams p(point, specs);
    const auto lat = p.number("lat", true);
    const auto lon = p.number("lon", true);
    const auto agl = p.number("alt", false);
    if (!p.ok()) return Error{p.error().code, where + p.error().message};
    if (!terrain)
        return Error{code::unavailable,
                     where + (above_ground ? "alt_ref 'terrain' needs" : "'alt' left out needs") +
                         " gimbald's terrain section, and none is configured: give 'alt'"};
    const auto h = terrain->height(*lat, *lon);
    if (!h)
        return Error{code::unavailable,
                     where + "the terrain has no height at " + command::format_number(*lat) + ", " +
                         command::format_number(*lon) +
                         " (outside the elevation model, or nodata): give 'alt'"};
    return *h + (above_ground ? agl.value_or(0.0) : 0.0);
}

command::Result<json> resolve_geopoint(const json& request, geo::Surface* terrain) {
    const auto read = alt_ref(request, "geopoint");
    if (!read) return read.error();
    const auto& ref = *read;
    const bool above_ground = ref == "terrain";
    if (present(request, "alt") && !above_ground) return request;
    if (ref == "msl")
        return Error{code::bad_request, "missing parameter 'alt' (alt_ref 'msl' needs it)"};
    auto alt = ground_altitude(request, specs_of("geopoint", ""), above_ground, terrain, "");
    if (!alt) return alt.error();
    json out = request;
    out["alt"] = *alt;
    out["alt_ref"] = "wgs84";
    return out;
}

command::Result<json> resolve_path(const json& request, geo::Surface* terrain) {
    const auto read = alt_ref(request, "path");
    if (!read) return read.error();
    const auto& ref = *read;
    const bool above_ground = ref == "terrain";
    const auto points = request.find("points");
    if (points == request.end() || !points->is_array()) return request;
    json out = request;
    bool changed = false;
    for (std::size_t i = 0; i < points->size(); ++i) {
        const json& point = (*points)[i];
        if (!point.is_object()) return request;  // the planner names the point
        if (present(point, "alt") && !above_ground) continue;
        auto alt = ground_altitude(point, specs_of("path", "points"), above_ground, terrain,
                                   "points[" + std::to_string(i) + "]: ");
        if (!alt) return alt.error();
        out["points"][i]["alt"] = *alt;
        changed = true;
    }
    if (!changed && !above_ground) return request;
    out["alt_ref"] = "wgs84";
    return out;
}

}  // namespace

bool takes_ground_altitudes(std::string_view cmd) {
    return cmd == "geopoint" || cmd == "path";
}

command::Result<json> resolve_ground_altitudes(std::string_view cmd, const json& request,
                                               geo::Surface* terrain) {
    if (!request.is_object()) return request;
    if (cmd == "geopoint") return resolve_geopoint(request, terrain);
    if (cmd == "path") return resolve_path(request, terrain);
    return request;
}

}  // namespace gimbal::session
