#include "state/ground_json.hpp"

#include <string>

#include "state/precision.hpp"

namespace gimbal::state {

nlohmann::json ground_point_json(const geo::GroundPoint& g) {
    return {{"lat", latlon_deg(g.point.lat_deg)},
            {"lon", latlon_deg(g.point.lon_deg)},
            {"alt", metres(g.point.alt_m)},
            {"range_m", metres(g.range_m)},
            {"surface", std::string(geo::to_string(g.surface))}};
}

void add_ground_keys(nlohmann::json& telemetry, const geo::CameraPose& camera,
                     const geo::Ground& ground) {
    if (const auto f = geo::ground_footprint(camera, ground)) {
        nlohmann::json corners = nlohmann::json::array();
        for (const auto& c : f->corners)
            corners.push_back({{"lat", latlon_deg(c.lat_deg)}, {"lon", latlon_deg(c.lon_deg)}});
        telemetry["footprint"] = std::move(corners);
        telemetry["footprint_surface"] = std::string(geo::to_string(f->surface));
    } else {
        telemetry["footprint"] = nullptr;
        telemetry["footprint_surface"] = nullptr;
    }
    const auto centre = geo::locate_ground(camera, {0, 0}, ground);
    telemetry["ground"] = centre ? ground_point_json(*centre) : nlohmann::json(nullptr);
}

}  // namespace gimbal::state
