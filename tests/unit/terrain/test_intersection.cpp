// Ray-terrain intersection on GeoTIFFs written here from analytic surfaces: within 0.5 m of
// the exact intersection with the model's bilinear surface at ranges up to 20 km, and the
// edge cases (leaving coverage, above the horizon, grazing a ridge, starting below ground).
#include <catch2/catch.hpp>
#include <random>

#include "terrain_fixture.hpp"

using namespace terrain_test;
using gimbal::geo::RayStatus;

namespace {

struct Case {
    const char* name;
    std::function<double(double, double)> fn;
    double max_slope;
};

double hill(double lat, double lon) {
    const double x = east_m(lon), y = north_m(lat);
    return 150 + 700 * std::exp(-(x * x + y * y) / (2 * 3000.0 * 3000.0));
}

// Random rays from 500-2500 m above the ground towards points 1-20 km away; every one is
// compared with the exact intersection.
void check_random_rays(geo::Surface& model, double max_slope, int count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0;
    double worst = 0, longest = 0;
    for (int i = 0; i < count; ++i) {
        const geo::Lla start{45.7 + (unit(rng) - 0.5) * 0.1, -121.5 + (unit(rng) - 0.5) * 0.1, 0};
        const double ground = *model.height(start.lat_deg, start.lon_deg);
        const geo::Lla from{start.lat_deg, start.lon_deg, ground + 500 + 2000 * unit(rng)};
        const double dist = 1000 + 19000 * unit(rng);
        const geo::Vec3 dir = towards(from, unit(rng) * 360, dist, 100);
        const auto got = model.intersect(from, dir, {30000});
        const auto want = exact_intersection(model, from, dir, 30000, max_slope);
        INFO("ray " << i << " want " << gimbal::geo::to_string(want.status) << " at "
                    << want.range_m << ", got " << gimbal::geo::to_string(got.status) << " at "
                    << got.range_m);
        REQUIRE(got.status == want.status);
        if (want.status != RayStatus::hit) continue;
        ++hits;
        REQUIRE(std::abs(got.range_m - want.range_m) < 0.5);
        // The reported point lies on the surface.
        REQUIRE(std::abs(got.point.alt_m - *model.height(got.point.lat_deg, got.point.lon_deg)) <
                0.05);
        worst = std::max(worst, std::abs(got.range_m - want.range_m));
        longest = std::max(longest, got.range_m);
    }
    CHECK(hits > count / 2);
    CHECK(longest > 12000);
    WARN("largest error " << worst << " m, longest hit " << longest << " m");
}

}  // namespace

TEST_CASE("intersection: analytic surfaces within 0.5 m up to 20 km", "[terrain]") {
    TempDir tmp;
    const std::vector<Case> cases{
        {"plane", [](double, double) { return 200.0; }, 0},
        {"slope",
         [](double lat, double lon) { return 300 + 0.05 * east_m(lon) + 0.02 * north_m(lat); },
         0.06},
        {"hill", hill, 0.2},
        // A 300 m cliff along a line between nodes: one cell of steep bilinear ramp.
        {"cliff", [](double lat, double) { return north_m(lat) < 1234.5 ? 100.0 : 400.0; }, 12},
    };
    std::uint64_t seed = 1;
    for (const auto& c : cases) {
        SECTION(c.name) {
            const auto path = tmp.file(std::string(c.name) + ".tif");
            REQUIRE(terrain::write_geotiff(path, demo_grid(), c.fn).empty());
            auto model = open_model({path});
            check_random_rays(*model, c.max_slope, 40, seed);
        }
        ++seed;
    }
}

TEST_CASE("intersection: a plane at known range", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("plane.tif");
    REQUIRE(
        terrain::write_geotiff(path, demo_grid(), [](double, double) { return 200.0; }).empty());
    auto model = open_model({path});
    // Straight down from 1200 m over a plane at 200 m: 1000 m.
    const geo::Lla from{45.7, -121.5, 1200};
    const auto down = model->intersect(from, geo::ned_to_ecef({0, 0, 1}, from), {});
    REQUIRE(down.status == RayStatus::hit);
    CHECK(down.range_m == Approx(1000).margin(1e-3));
    CHECK(down.point.alt_m == Approx(200).margin(1e-3));
    // The same as the ellipsoid raised to 200 m, at a slant.
    geo::EllipsoidSurface flat(200);
    const geo::Vec3 slant = geo::ned_to_ecef({0.6, 0.5, 0.12}, from);
    const auto a = model->intersect(from, slant, {});
    const auto b = flat.intersect(from, slant, {});
    REQUIRE(a.status == RayStatus::hit);
    REQUIRE(b.status == RayStatus::hit);
    CHECK(std::abs(a.range_m - b.range_m) < 0.05);
    CHECK(distance_m(a.point, b.point) < 0.05);
}

TEST_CASE("intersection: leaving coverage, above the horizon, below ground", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("hill.tif");
    REQUIRE(terrain::write_geotiff(path, demo_grid(), hill).empty());
    auto model = open_model({path});
    const geo::Lla from{45.85, -121.5, 1500};

    // North and gently down: the ground it would reach lies beyond the model's north edge.
    const auto out = model->intersect(from, geo::ned_to_ecef({1, 0, 0.02}, from), {});
    CHECK(out.status == RayStatus::unknown);
    CHECK(out.point.lat_deg == Approx(45.9).margin(1e-3));

    // Above the horizon: rises out of reach of any ground.
    const auto up = model->intersect(from, geo::ned_to_ecef({1, 0, -0.1}, from), {});
    CHECK(up.status == RayStatus::unknown);  // leaves the model before it climbs past 9 km
    const auto up_steep = model->intersect(from, geo::ned_to_ecef({0.2, 0, -1}, from), {});
    CHECK(up_steep.status == RayStatus::no_ground);

    // Level over the hill's foot, never descending to it within max range.
    const geo::Lla low{45.7, -121.5, 1000};
    const auto level = model->intersect(low, geo::ned_to_ecef({0, 1, 0}, low), {3000});
    CHECK(level.status == RayStatus::no_ground);
    CHECK(level.range_m == Approx(3000));

    // Starting below the surface (the hilltop is at 850 m).
    const geo::Lla under{45.7, -121.5, 700};
    CHECK(model->intersect(under, geo::ned_to_ecef({1, 0, 0}, under), {}).status ==
          RayStatus::below_surface);
    // Starting outside the model.
    const geo::Lla away{46.5, -121.5, 1500};
    CHECK(model->intersect(away, geo::ned_to_ecef({0, 0, 1}, away), {}).status ==
          RayStatus::unknown);
    // Invalid input.
    CHECK(model->intersect(from, {0, 0, 0}, {}).status == RayStatus::invalid);
    CHECK(model->intersect({NAN, 0, 0}, {1, 0, 0}, {}).status == RayStatus::invalid);
}

TEST_CASE("intersection: grazing rays do not skip a one-node ridge", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("ridge.tif");
    // Flat at 100 m with one diagonal line of nodes at 300 m: a ridge one cell wide whose
    // cells are saddles (the highest point along a ray can lie inside a cell).
    const double s = 1.0 / 3600;
    REQUIRE(terrain::write_geotiff(path, demo_grid(), [s](double lat, double lon) {
                const long i = std::lround((45.9 - lat) / s), j = std::lround((lon + 121.7) / s);
                return i - 720 == j - 720 ? 300.0 : 100.0;
            }).empty());
    auto model = open_model({path});
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    int hits = 0, misses = 0;
    for (int k = 0; k < 60; ++k) {
        // Level-ish rays crossing the ridge near 45.7 N -121.5 from either side at heights
        // from 110 to 320 m.
        const double side = k % 2 ? 1 : -1;
        const geo::Lla from{45.7 + side * 0.004 + (unit(rng) - 0.5) * 0.002,
                            -121.5 - side * 0.004 + (unit(rng) - 0.5) * 0.002,
                            110 + 210 * unit(rng)};
        const double az = (side > 0 ? 135 : 315) + (unit(rng) - 0.5) * 120;
        const geo::Vec3 dir = geo::ned_to_ecef(
            {std::cos(az * geo::deg2rad), std::sin(az * geo::deg2rad), (unit(rng) - 0.5) * 0.01},
            from);
        const auto got = model->intersect(from, dir, {1500});
        const auto want = exact_intersection(*model, from, dir, 1500, 10, 0.02);
        INFO("ray " << k);
        REQUIRE(got.status == want.status);
        if (want.status == RayStatus::hit) {
            ++hits;
            REQUIRE(std::abs(got.range_m - want.range_m) < 0.5);
        } else {
            ++misses;
        }
    }
    CHECK(hits > 10);
    CHECK(misses > 5);
}

TEST_CASE("intersection: the analytic surface and its GeoTIFF agree", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("hill.tif");
    REQUIRE(terrain::write_geotiff(path, demo_grid(), hill).empty());
    auto model = open_model({path});
    geo::SampledSurface sampled(hill, {45.5, -121.7, 1.0 / 3600, 1.0 / 3600}, 900,
                                geo::GeoRect{45.5, 45.9, -121.7, -121.3});
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 30; ++i) {
        const geo::Lla from{45.7 + (unit(rng) - 0.5) * 0.1, -121.5 + (unit(rng) - 0.5) * 0.1, 2000};
        const geo::Vec3 dir = towards(from, unit(rng) * 360, 2000 + unit(rng) * 8000, 150);
        const auto a = model->intersect(from, dir, {});
        const auto b = sampled.intersect(from, dir, {});
        REQUIRE(a.status == b.status);
        if (a.status == RayStatus::hit) CHECK(std::abs(a.range_m - b.range_m) < 0.01);
    }
}
