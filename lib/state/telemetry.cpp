#include "state/telemetry.hpp"

#include "state/precision.hpp"

namespace gimbal::state {

geo::GroundPoint rounded(const geo::GroundPoint& g) {
    return {{latlon_deg(g.point.lat_deg), latlon_deg(g.point.lon_deg), metres(g.point.alt_m)},
            metres(g.range_m),
            g.surface};
}

GroundView ground_view(const geo::CameraPose& camera, const geo::Ground& ground) {
    GroundView v;
    if (const auto f = geo::ground_footprint(camera, ground)) {
        std::array<LatLon, 4> corners{};
        for (std::size_t i = 0; i < 4; ++i)
            corners[i] = {latlon_deg(f->corners[i].lat_deg), latlon_deg(f->corners[i].lon_deg)};
        v.footprint = corners;
        v.footprint_surface = f->surface;
    }
    if (const auto centre = geo::locate_ground(camera, {0, 0}, ground)) v.ground = rounded(*centre);
    return v;
}

}  // namespace gimbal::state
