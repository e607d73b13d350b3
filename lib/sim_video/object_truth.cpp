#include "sim_video/object_truth.hpp"

#include <algorithm>
#include <cmath>

#include "geo/wgs84.hpp"
#include "sim/terrain_ray.hpp"

namespace gimbal::sim_video {

namespace {

// A ray that meets the terrain this much short of the object is blocked by a hill.
constexpr double terrain_tolerance_m = 3;

bool inside(const geo::ImagePoint& p) {
    return std::abs(p.x) <= 1 && std::abs(p.y) <= 1;
}

// The point `u` metres along the object's nose and `v` to its right.
sim::TerrainXY body_point(const sim::ObjectState& o, double u, double v) {
    const double h = o.heading_deg * geo::deg2rad;
    const double fe = std::sin(h), fn = std::cos(h);
    return {o.xy.east_m + u * fe + v * fn, o.xy.north_m + u * fn - v * fe};
}

geo::Lla on_ground(sim::TerrainXY p) {
    const geo::LatLon ll = sim::terrain_lat_lon(p);
    return {ll.lat_deg, ll.lon_deg, sim::terrain_height_xy(p)};
}

bool behind_terrain(const sim::TerrainRayCaster& caster, const geo::Lla& eye,
                    const geo::Lla& point) {
    const geo::Vec3 ray = geo::ecef_to_ned(geo::lla_to_ecef(point) - geo::lla_to_ecef(eye), eye);
    const auto hit = caster.cast(ray);
    if (hit.status == sim::TerrainRayCaster::Status::below) return true;
    return hit.status == sim::TerrainRayCaster::Status::hit &&
           hit.range_m < geo::norm(ray) - terrain_tolerance_m;
}

}  // namespace

std::vector<ObjectTruth> object_truth(const geo::CameraPose& camera,
                                      std::span<const sim::ObjectState> objects) {
    std::vector<ObjectTruth> out;
    if (!geo::valid(camera)) return out;
    const sim::TerrainRayCaster caster(camera.position);
    const geo::Vec3 eye = geo::lla_to_ecef(camera.position);
    for (const sim::ObjectState& o : objects) {
        ObjectTruth t;
        t.state = o;
        t.slant_range_m = geo::norm(geo::lla_to_ecef(o.position) - eye);
        const auto centre = geo::project(camera, o.position);
        if (centre && centre->in_front) {
            t.at = centre->at;
            t.in_picture = inside(centre->at);
        }
        const double hl = o.spec().length_m / 2, hw = o.spec().width_m / 2;
        ImageBox box{1e300, 1e300, -1e300, -1e300};
        bool all_in_front = true;
        for (const double u : {-hl, hl})
            for (const double v : {-hw, hw}) {
                const auto p = geo::project(camera, on_ground(body_point(o, u, v)));
                if (!p || !p->in_front) {
                    all_in_front = false;
                    continue;
                }
                box = {std::min(box.x0, p->at.x), std::min(box.y0, p->at.y),
                       std::max(box.x1, p->at.x), std::max(box.y1, p->at.y)};
            }
        if (all_in_front) t.box = box;
        // Behind the terrain: one ray, to the centre (an object is small beside a hill).
        const bool blocked = behind_terrain(caster, camera.position, o.position);
        if (blocked)
            t.hidden = ObjectTruth::Hidden::terrain;
        else if (sim::under_deck(o.xy, o.level))
            t.hidden = ObjectTruth::Hidden::deck;
        int seen = 0, samples = 0;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 3; ++j) {
                ++samples;
                const double u = hl * (i - 2) / 2.5, v = hw * (j - 1) / 1.5;
                const sim::TerrainXY p = body_point(o, u, v);
                const auto at = geo::project(camera, on_ground(p));
                if (!blocked && at && at->in_front && inside(at->at) &&
                    !sim::under_deck(p, o.level))
                    ++seen;
            }
        t.visible_fraction = static_cast<double>(seen) / samples;
        out.push_back(t);
    }
    return out;
}

}  // namespace gimbal::sim_video
