#include "command/path_request.hpp"

#include <array>
#include <string>
#include <string_view>

#include "geo/wgs84.hpp"

namespace gimbal::command {

Result<PathRequest> read_path_request(JsonParams& p) {
    PathRequest r;
    const nlohmann::json* points = p.raw("points");
    r.down = p.boolean_or("down", false);
    r.along_step_deg = p.number_or("along_step_deg", 0.0);
    r.cross_steps = static_cast<unsigned>(p.integer_or("cross_steps", 0));
    r.cross_ratio = p.number_or("cross_ratio", 0.0);
    const auto ref = p.choice("alt_ref", false).value_or("wgs84");
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (ref == "terrain")
        return Error{code::unavailable, "alt_ref 'terrain' needs gimbald's terrain section"};
    if (r.down) {
        if (points) return Error{code::bad_request, "'down': true takes no 'points'"};
        return r;
    }
    if (!points) return Error{code::bad_request, "missing parameter 'points' (or 'down': true)"};
    if (!points->is_array() || points->empty())
        return Error{code::bad_request, "'points' must be an array of 1 to 15 points"};
    if (points->size() > max_path_points)
        return Error{code::out_of_range, "'points' must hold 1 to 15 points"};
    for (std::size_t i = 0; i < points->size(); ++i) {
        const auto& item = (*points)[i];
        const std::string where = "points[" + std::to_string(i) + "]";
        if (!item.is_object())
            return Error{code::bad_request, where + " must be {\"lat\",\"lon\",\"alt\"}"};
        JsonParams point(item, p.fields_of("points"));
        const auto lat = point.number("lat", true);
        const auto lon = point.number("lon", true);
        const auto alt = point.number("alt", true);
        point.reject_unknown();
        if (!point.ok()) return Error{point.error().code, where + ": " + point.error().message};
        r.ecef.push_back(geo::lla_to_ecef({*lat, *lon, *alt}));
    }
    return r;
}

}  // namespace gimbal::command
