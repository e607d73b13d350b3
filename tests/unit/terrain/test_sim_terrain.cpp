// The simulator's terrain written as a GeoTIFF and read back through the elevation model.
#include <catch2/catch.hpp>
#include <random>

#include "sim/terrain.hpp"
#include "terrain_fixture.hpp"

using namespace terrain_test;

TEST_CASE("sim terrain: the written GeoTIFF equals the analytic heights", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("sim.tif");
    // Bounds on whole arc-seconds, so the file's lattice is the simulator's.
    const terrain::GridSpec spec{45.62, 45.78, -121.62, -121.38, 1.0 / 3600};
    REQUIRE(terrain::write_geotiff(path, spec, sim::terrain_height).empty());
    auto model = open_model({path});
    auto surface = sim::terrain_surface();
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> unit(0, 1);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const double lat = 45.62 + unit(rng) * 0.16, lon = -121.62 + unit(rng) * 0.24;
        const auto h = model->height(lat, lon);
        REQUIRE(h);
        CHECK(*h == Approx(sim::terrain_height(lat, lon)).margin(0.5));
        CHECK(*h == Approx(surface->height(lat, lon).value()).margin(1e-3));
        worst = std::max(worst, std::abs(*h - sim::terrain_height(lat, lon)));
    }
    WARN("largest difference from the analytic terrain: " << worst << " m");
}

TEST_CASE("sim terrain: relief, bound and landmarks", "[terrain]") {
    double lo = 1e9, hi = -1e9;
    for (double y = -20000; y <= 20000; y += 100)
        for (double x = -20000; x <= 20000; x += 100) {
            const double lat = 45.7 + y / 111130, lon = -121.5 + x / 77900;
            const double h = sim::terrain_height(lat, lon);
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
    // Several hundred metres of relief, below the bound and well below the aircraft.
    CHECK(hi - lo > 500);
    CHECK(hi < sim::terrain_max_alt_m - 50);
    CHECK(lo > 0);
    const auto& marks = sim::landmarks();
    REQUIRE(marks.size() >= 4);
    for (const auto& m : marks) {
        CHECK(m.alt_m == Approx(sim::terrain_height(m.lat_deg, m.lon_deg)).margin(1e-6));
        CHECK(std::abs(m.lat_deg - 45.7) < 0.1);
        CHECK(std::abs(m.lon_deg + 121.5) < 0.1);
    }
    // The bridge lies in the valley, the summit on a hill.
    const auto find = [&](const std::string& name) {
        for (const auto& m : marks)
            if (m.name == name) return m;
        FAIL("no landmark " << name);
        return marks.front();
    };
    CHECK(find("summit").alt_m - find("bridge").alt_m > 500);
}
