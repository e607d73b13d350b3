// The EGM96 geoid from proj-data's grid, against NGA's published EGM96 values (the sample
// output of its interpolation program, README of WW15MGH), and DEM heights above it.
#include <catch2/catch.hpp>

#include "terrain/geoid.hpp"
#include "terrain_fixture.hpp"

using namespace terrain_test;

TEST_CASE("geoid: EGM96 undulations match NGA's within 1 m", "[terrain]") {
    const auto path = terrain::Geoid::find_egm96();
    REQUIRE(path);
    const auto opened = terrain::Geoid::open(*path);
    REQUIRE(opened);
    const auto& g = *opened;
    struct Point {
        double lat, lon, n;
    };
    // lat, lon (0..360 east), N in metres.
    for (const Point& p :
         {Point{38.6281550, 269.7791550, -31.628}, Point{-14.6212170, 305.0211140, -2.969},
          Point{46.8743190, 102.4487290, -43.575}, Point{-23.6174460, 133.8747120, 15.871},
          Point{38.6254730, 359.9995000, 50.066}, Point{-0.4667440, 0.0023000, 17.329}}) {
        INFO(p.lat << " " << p.lon);
        CHECK(g.undulation(p.lat, p.lon) == Approx(p.n).margin(1.0));
        CHECK(g.undulation(p.lat, p.lon - 360) == Approx(p.n).margin(1.0));
    }
    // The demo area: about -21 m.
    CHECK(g.undulation(45.7, -121.5) == Approx(-21).margin(2));
}

TEST_CASE("geoid: heights above EGM96 become ellipsoid heights", "[terrain]") {
    TempDir tmp;
    const auto path = tmp.file("msl.tif");
    REQUIRE(
        terrain::write_geotiff(path, {45.6, 45.8, -121.6, -121.4, 1.0 / 3600}, [](double, double) {
            return 500.0;
        }).empty());
    auto msl = open_model({path}, terrain::GeoidModel::egm96);
    auto ell = open_model({path}, terrain::GeoidModel::none);
    const auto n = msl->geoid_undulation(45.7, -121.5);
    REQUIRE(n);
    CHECK_FALSE(ell->geoid_undulation(45.7, -121.5));
    CHECK(msl->height(45.7, -121.5).value() == Approx(500 + *n).margin(0.01));
    CHECK(ell->height(45.7, -121.5).value() == Approx(500));
    const auto e = msl->elevation(45.7, -121.5);
    REQUIRE(e);
    CHECK(e->alt_msl_m.value() == Approx(500).margin(0.01));
    CHECK(e->source == path);
    CHECK_FALSE(ell->elevation(45.7, -121.5)->alt_msl_m);
    // The ground straight below meets the ellipsoid height.
    const geo::Lla from{45.7, -121.5, 1500};
    const auto hit = msl->intersect(from, geo::ned_to_ecef({0, 0, 1}, from), {});
    CHECK(hit.point.alt_m == Approx(500 + *n).margin(0.01));
}
