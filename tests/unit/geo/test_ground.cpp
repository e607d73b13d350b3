// The ground gimbald answers with (geo/ground.hpp): the terrain where it answers, else the
// ellipsoid raised to the flat world's altitude, for single rays and for the footprint.
#include <catch2/catch.hpp>

#include "geo/ground.hpp"
#include "geo/sampled_surface.hpp"

using namespace gimbal::geo;

namespace {

// A plateau at 400 m covering 45.6..45.8 N, 121.6..121.4 W; unknown outside.
SampledSurface plateau() {
    return SampledSurface([](double, double) { return 400.0; }, Lattice{}, 400.0,
                          GeoRect{45.6, 45.8, -121.6, -121.4});
}

CameraPose looking(double pan, double tilt, double lat = 45.7, double lon = -121.5) {
    return camera_pose({lat, lon, 1500}, Quat{}, pan, tilt, 40, 30);
}

}  // namespace

TEST_CASE("ground: the terrain first, the flat world where it has no answer", "[ground]") {
    auto terrain = plateau();
    RayStatus why = RayStatus::hit;

    // Inside the terrain: on it, at 1100 m below the camera.
    auto g = locate_ground(looking(0, -90), {0, 0}, {&terrain, 100.0}, &why);
    REQUIRE(g);
    CHECK(g->surface == SurfaceKind::terrain);
    CHECK(g->point.alt_m == Approx(400).margin(1e-6));
    CHECK(g->range_m == Approx(1100).margin(1e-3));

    // Looking out of the terrain's coverage: the flat world at 100 m.
    const CameraPose edge = looking(0, -90, 45.9, -121.5);
    g = locate_ground(edge, {0, 0}, {&terrain, 100.0}, &why);
    REQUIRE(g);
    CHECK(g->surface == SurfaceKind::ellipsoid);
    CHECK(g->point.alt_m == Approx(100).margin(1e-3));
    CHECK(g->range_m == Approx(1400).margin(1e-2));
    // ... and nothing without a flat world, saying why.
    CHECK_FALSE(locate_ground(edge, {0, 0}, {&terrain, std::nullopt}, &why));
    CHECK(why == RayStatus::unknown);

    // No terrain configured: the flat world alone; with neither, unknown.
    g = locate_ground(looking(0, -90), {0, 0}, {nullptr, 100.0});
    REQUIRE(g);
    CHECK(g->surface == SurfaceKind::ellipsoid);
    CHECK_FALSE(locate_ground(looking(0, -90), {0, 0}, {nullptr, std::nullopt}, &why));
    CHECK(why == RayStatus::unknown);

    // Above the horizon: no ground on either.
    CHECK_FALSE(locate_ground(looking(0, 10), {0, 0}, {&terrain, 100.0}, &why));
    CHECK(why == RayStatus::no_ground);

    // An invalid camera is no ground at all.
    CameraPose bad = looking(0, -90);
    bad.hfov_deg = 0;
    CHECK_FALSE(locate_ground(bad, {0, 0}, {&terrain, 100.0}, &why));
    CHECK(why == RayStatus::invalid);
}

TEST_CASE("ground: the footprint on the terrain when every corner meets it", "[ground]") {
    auto terrain = plateau();
    const auto f = ground_footprint(looking(0, -90), {&terrain, 100.0});
    REQUIRE(f);
    CHECK(f->surface == SurfaceKind::terrain);
    for (const auto& c : f->corners) CHECK(c.alt_m == Approx(400).margin(1e-6));
    // The corners are locate_ground's.
    const ImagePoint corners[] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto g = locate_ground(looking(0, -90), corners[i], {&terrain, 100.0});
        REQUIRE(g);
        CHECK(norm(lla_to_ecef(g->point) - lla_to_ecef(f->corners[i])) < 1e-6);
    }
    // A corner beyond the coverage: the whole footprint falls back to the flat world.
    const auto flat = ground_footprint(looking(0, -90, 45.8, -121.5), {&terrain, 100.0});
    REQUIRE(flat);
    CHECK(flat->surface == SurfaceKind::ellipsoid);
    const auto old = footprint(looking(0, -90, 45.8, -121.5), 100.0);
    REQUIRE(old);
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(flat->corners[i].lat_deg == Approx((*old)[i].lat_deg).margin(1e-9));
        CHECK(flat->corners[i].lon_deg == Approx((*old)[i].lon_deg).margin(1e-9));
    }
    CHECK_FALSE(ground_footprint(looking(0, -90, 45.8, -121.5), {&terrain, std::nullopt}));
    // Corners above the horizon: none.
    CHECK_FALSE(ground_footprint(looking(0, 0), {&terrain, 100.0}));
}
