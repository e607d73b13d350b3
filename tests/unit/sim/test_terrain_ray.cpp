// The video renderer's ray caster against the analytic terrain: hits on the terrain, the first
// crossing (no ridge stepped over), agreement with geo::locate on terrain_surface(), sky and a
// camera under ground; the slope bound and the march grid's bound it relies on.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geo/image.hpp"
#include "sim/terrain.hpp"
#include "sim/terrain_grid.hpp"
#include "sim/terrain_ray.hpp"

using namespace gimbal;
using sim::TerrainRayCaster;

namespace {

double gap_at(const geo::Lla& from, const geo::Vec3& dir_ned, double t) {
    const geo::Vec3 d = (1 / geo::norm(dir_ned)) * dir_ned;
    const geo::Lla p = geo::ecef_to_lla(geo::lla_to_ecef(from) + t * geo::ned_to_ecef(d, from));
    return p.alt_m - sim::terrain_height(p.lat_deg, p.lon_deg);
}

geo::Vec3 direction(double azimuth_deg, double depression_deg) {
    const double a = azimuth_deg * geo::deg2rad, e = depression_deg * geo::deg2rad;
    return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

}  // namespace

TEST_CASE("terrain ray: the first crossing of the analytic terrain", "[sim][terrain_ray]") {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
        const geo::Lla from{45.7 + (unit(rng) - 0.5) * 0.08, -121.5 + (unit(rng) - 0.5) * 0.1,
                            800 + unit(rng) * 1700};
        const double depression = 0.5 + std::pow(unit(rng), 2) * 89;
        const geo::Vec3 dir = direction(unit(rng) * 360, depression);
        const TerrainRayCaster caster(from, 30000);
        const auto r = caster.cast(dir);
        if (r.status == TerrainRayCaster::Status::below) {
            CHECK(from.alt_m <= sim::terrain_height(from.lat_deg, from.lon_deg));
            continue;
        }
        if (r.status == TerrainRayCaster::Status::miss) {
            // Nothing within range: the ray stays above the ground all the way.
            for (double t = 0; t < 30000; t += 25) REQUIRE(gap_at(from, dir, t) > -0.05);
            continue;
        }
        ++hits;
        // On the terrain, within the range, and xy is the point's.
        CHECK(std::abs(r.point.alt_m - sim::terrain_height(r.point.lat_deg, r.point.lon_deg)) <
              0.02);
        CHECK(r.range_m <= 30000);
        CHECK(std::abs(gap_at(from, dir, r.range_m)) < 0.02);
        const sim::TerrainXY xy = sim::terrain_xy(r.point.lat_deg, r.point.lon_deg);
        CHECK(xy.east_m == Approx(r.xy.east_m).margin(1e-6));
        CHECK(xy.north_m == Approx(r.xy.north_m).margin(1e-6));
        // The first crossing: above the ground everywhere before it (10 m samples).
        for (double t = 0; t < r.range_m - 1; t += 10) REQUIRE(gap_at(from, dir, t) > -0.02);
    }
    CHECK(hits > 200);
}

TEST_CASE("terrain ray: agrees with geo::locate on the 1 arc-second terrain",
          "[sim][terrain_ray]") {
    auto surface = sim::terrain_surface();
    const geo::Lla from{45.69, -121.51, 1500};
    const TerrainRayCaster caster(from, 30000);
    int compared = 0;
    for (double az = 0; az < 360; az += 15)
        for (double depression : {12.0, 25.0, 45.0, 70.0, 89.0}) {
            const geo::Vec3 dir = direction(az, depression);
            const auto r = caster.cast(dir);
            const auto hit = surface->intersect(from, geo::ned_to_ecef(dir, from), {});
            REQUIRE(r.status == TerrainRayCaster::Status::hit);
            REQUIRE(hit.status == geo::RayStatus::hit);
            // The lattice's bilinear surface lies within half a metre of the analytic one; at
            // 12 degrees that moves the hit a few metres along the ray.
            CHECK(std::abs(r.range_m - hit.range_m) < 0.6 / std::sin(depression * geo::deg2rad));
            ++compared;
        }
    CHECK(compared == 120);
}

TEST_CASE("terrain ray: sky, range and a camera under the ground", "[sim][terrain_ray]") {
    const TerrainRayCaster high({45.7, -121.5, 1500}, 30000);
    CHECK(high.cast({1, 0, -0.1}).status == TerrainRayCaster::Status::miss);  // above the horizon
    CHECK(high.cast({0, 0, 0}).status == TerrainRayCaster::Status::miss);     // no direction
    CHECK(high.cast({0, 0, 1}).status == TerrainRayCaster::Status::hit);
    // Nearly level: the ground is far beyond a short range.
    const TerrainRayCaster short_range({45.7, -121.5, 1500}, 2000);
    CHECK(short_range.cast(direction(0, 2)).status == TerrainRayCaster::Status::miss);
    CHECK(short_range.cast(direction(0, 80)).status == TerrainRayCaster::Status::hit);
    const double ground = sim::terrain_height(45.7, -121.5);
    const TerrainRayCaster buried({45.7, -121.5, ground - 5}, 30000);
    CHECK(buried.cast({0, 0, 1}).status == TerrainRayCaster::Status::below);
}

TEST_CASE("terrain ray: the slope bound and the march grid hold", "[sim][terrain_ray]") {
    // Steepest slope on a 50 m lattice over 40 x 40 km: under the bound the march assumes.
    double steepest = 0;
    for (double y = -20000; y <= 20000; y += 50)
        for (double x = -20000; x <= 20000; x += 50) {
            const double h = sim::terrain_height_xy({x, y});
            const double gx = (sim::terrain_height_xy({x + 1, y}) - h);
            const double gy = (sim::terrain_height_xy({x, y + 1}) - h);
            steepest = std::max(steepest, std::hypot(gx, gy));
        }
    CHECK(steepest < 0.9 * sim::terrain_max_slope);
    // The grid lies nowhere below the terrain, and not far above it.
    const auto& grid = sim::TerrainGrid::instance();
    CHECK(grid.error_bound_m() < 10);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coord(-40000, 40000);
    for (int i = 0; i < 100000; ++i) {
        const sim::TerrainXY p{coord(rng), coord(rng)};
        const double h = sim::terrain_height_xy(p);
        const double bound = grid.upper_bound(p);
        REQUIRE(bound >= h);
        REQUIRE(bound - h <= 2 * grid.error_bound_m());
    }
}

TEST_CASE("terrain: the local grid and the river", "[sim][terrain]") {
    for (const auto& m : sim::landmarks()) {
        const sim::TerrainXY xy = sim::terrain_xy(m.lat_deg, m.lon_deg);
        const geo::LatLon back = sim::terrain_lat_lon(xy);
        CHECK(back.lat_deg == Approx(m.lat_deg).margin(1e-12));
        CHECK(back.lon_deg == Approx(m.lon_deg).margin(1e-12));
        CHECK(sim::terrain_height_xy(xy) == Approx(m.alt_m).margin(1e-6));
    }
    // One kilometre of the grid is one kilometre on the ground (within the projection's
    // distortion this close to the origin).
    const geo::LatLon a = sim::terrain_lat_lon({0, 0}), b = sim::terrain_lat_lon({1000, 0});
    const geo::LatLon c = sim::terrain_lat_lon({0, 1000});
    CHECK(geo::look_angles({a.lat_deg, a.lon_deg, 0}, {b.lat_deg, b.lon_deg, 0}).range_m ==
          Approx(1000).epsilon(1e-4));
    CHECK(geo::look_angles({a.lat_deg, a.lon_deg, 0}, {c.lat_deg, c.lon_deg, 0}).range_m ==
          Approx(1000).epsilon(1e-4));
    // The river runs along the valley floor: lower than the banks 1 km either side.
    for (double x = -8000; x <= 8000; x += 1000) {
        const double y = sim::river_north_m(x);
        CHECK(sim::terrain_height_xy({x, y}) < sim::terrain_height_xy({x, y + 1000}) - 100);
        CHECK(sim::terrain_height_xy({x, y}) < sim::terrain_height_xy({x, y - 1000}) - 100);
    }
    const auto& bridge = sim::landmarks()[2];
    REQUIRE(bridge.name == "bridge");
    const sim::TerrainXY bxy = sim::terrain_xy(bridge.lat_deg, bridge.lon_deg);
    CHECK(sim::river_north_m(bxy.east_m) == Approx(bxy.north_m).margin(1e-6));
}
