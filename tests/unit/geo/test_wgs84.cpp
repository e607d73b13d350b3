// WGS84 positions, NED axes, line-of-sight targets, look angles and MSL altitude.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "geo/wgs84.hpp"

using namespace gimbal::geo;

namespace {

constexpr double a = 6378137.0;        // WGS84 semi-major axis
constexpr double b = 6356752.314245;   // semi-minor axis
const Lla hood{45.7, -121.5, 1500.0};  // a point over the Columbia River Gorge

void check_vec(const Vec3& got, const Vec3& want, double tolerance) {
    CHECK(got.x == Approx(want.x).margin(tolerance));
    CHECK(got.y == Approx(want.y).margin(tolerance));
    CHECK(got.z == Approx(want.z).margin(tolerance));
}

}  // namespace

TEST_CASE("ECEF of known geodetic points", "[geo][ecef]") {
    check_vec(lla_to_ecef({0, 0, 0}), {a, 0, 0}, 1e-6);
    check_vec(lla_to_ecef({0, 90, 0}), {0, a, 0}, 1e-6);
    check_vec(lla_to_ecef({0, 180, 0}), {-a, 0, 0}, 1e-6);
    check_vec(lla_to_ecef({0, 0, 1000}), {a + 1000, 0, 0}, 1e-6);
    check_vec(lla_to_ecef({90, 0, 0}), {0, 0, b}, 1e-6);
    check_vec(lla_to_ecef({-90, 0, 100}), {0, 0, -b - 100}, 1e-6);
    // N = a / sqrt(1 - e^2 sin^2(lat)); X = (N + h) cos(lat) cos(lon), ..., Z = (N(1-e^2) + h)
    // sin(lat)
    check_vec(lla_to_ecef(hood), {-2332064.1951, -3805582.8913, 4543095.3438}, 1e-3);
    check_vec(lla_to_ecef({-33.9, 151.2, 50}), {-4643982.3947, 2553050.9262, -3537273.2352}, 1e-3);
}

TEST_CASE("ECEF -> geodetic inverts geodetic -> ECEF", "[geo][ecef]") {
    for (const Lla p : {hood, Lla{0, 0, 0}, Lla{-33.9, 151.2, 50}, Lla{89.999, 10, 12000},
                        Lla{-60, -179.9, -100}, Lla{12.5, 45, 35786000}}) {
        const Lla back = ecef_to_lla(lla_to_ecef(p));
        CHECK(back.lat_deg == Approx(p.lat_deg).margin(1e-9));
        CHECK(back.lon_deg == Approx(p.lon_deg).margin(1e-9));
        CHECK(back.alt_m == Approx(p.alt_m).margin(1e-6));
    }
    const Lla pole = ecef_to_lla({0, 0, b + 10});
    CHECK(pole.lat_deg == Approx(90.0));
    CHECK(pole.alt_m == Approx(10.0).margin(1e-6));
}

TEST_CASE("NED axes at known points", "[geo][ned]") {
    // On the equator at longitude 0: north is +Z, east is +Y, down is -X.
    check_vec(ecef_to_ned({0, 0, 1}, {0, 0, 0}), {1, 0, 0}, 1e-12);
    check_vec(ecef_to_ned({0, 1, 0}, {0, 0, 0}), {0, 1, 0}, 1e-12);
    check_vec(ecef_to_ned({1, 0, 0}, {0, 0, 0}), {0, 0, -1}, 1e-12);
    // At the north pole, down is -Z whatever the longitude.
    check_vec(ned_to_ecef({0, 0, 1}, {90, 37, 0}), {0, 0, -1}, 1e-12);
    // At longitude 90 on the equator, east is -X.
    check_vec(ned_to_ecef({0, 1, 0}, {0, 90, 0}), {-1, 0, 0}, 1e-12);
}

TEST_CASE("NED <-> ECEF is a rotation", "[geo][ned]") {
    const Vec3 v{123.0, -456.0, 789.0};
    for (const Lla at : {hood, Lla{-33.9, 151.2, 0}, Lla{0, 0, 0}, Lla{80, -170, 0}}) {
        const Vec3 ned = ecef_to_ned(v, at);
        CHECK(norm(ned) == Approx(norm(v)));
        check_vec(ned_to_ecef(ned, at), v, 1e-9);
    }
    // Down is the ellipsoid normal: the position moves along it when only the height changes.
    const Vec3 up_1km = lla_to_ecef({hood.lat_deg, hood.lon_deg, 2500}) - lla_to_ecef(hood);
    check_vec(ecef_to_ned(up_1km, hood), {0, 0, -1000}, 1e-6);
}

TEST_CASE("target = gimbal position + line of sight", "[geo][target]") {
    SECTION("straight down along the local vertical") {
        const auto t = target_from_los(hood, ned_to_ecef({0, 0, 1500}, hood));
        REQUIRE(t);
        CHECK(t->lat_deg == Approx(hood.lat_deg).margin(1e-9));
        CHECK(t->lon_deg == Approx(hood.lon_deg).margin(1e-9));
        CHECK(t->alt_m == Approx(0.0).margin(1e-6));
    }
    SECTION("1 km north, level") {
        const auto t = target_from_los(hood, ned_to_ecef({1000, 0, 0}, hood));
        REQUIRE(t);
        // Meridional radius M = a(1-e^2) / (1 - e^2 sin^2 lat)^1.5 = 6368165.6 m at 45.7 N,
        // so 1 km is 1000 / (M + h) rad of latitude; the level line rises h^2 / 2R above it.
        CHECK(t->lat_deg == Approx(45.7 + 1000.0 / (6368165.6 + 1500.0) * 180.0 / pi).margin(1e-6));
        CHECK(t->lon_deg == Approx(hood.lon_deg).margin(1e-9));
        CHECK(t->alt_m == Approx(1500.0 + 1000.0 * 1000.0 / (2 * 6368165.6)).margin(2e-3));
    }
    SECTION("a telemetry-sized ECEF vector") {
        const Vec3 los{-250.0, 400.0, -900.0};
        const auto t = target_from_los(hood, los);
        REQUIRE(t);
        check_vec(lla_to_ecef(*t) - lla_to_ecef(hood), los, 1e-6);
    }
    SECTION("no target without a vector") {
        CHECK_FALSE(target_from_los(hood, {0, 0, 0}));
        CHECK_FALSE(target_from_los(hood, {std::numeric_limits<double>::quiet_NaN(), 1, 1}));
    }
}

TEST_CASE("look angles from one point to another", "[geo][look]") {
    SECTION("straight down") {
        const LookAngles l = look_angles(hood, {hood.lat_deg, hood.lon_deg, 0});
        CHECK(l.elevation_deg == Approx(-90.0));
        CHECK(l.range_m == Approx(1500.0));
    }
    SECTION("north, east, south, west on the local level") {
        const struct {
            Vec3 ned;
            double azimuth;
        } cases[] = {
            {{1000, 0, 0}, 0}, {{0, 1000, 0}, 90}, {{-1000, 0, 0}, 180}, {{0, -1000, 0}, -90}};
        for (const auto& c : cases) {
            const auto to = target_from_los(hood, ned_to_ecef(c.ned, hood));
            REQUIRE(to);
            const LookAngles l = look_angles(hood, *to);
            CHECK(std::fabs(std::remainder(l.azimuth_deg - c.azimuth, 360.0)) < 1e-6);
            CHECK(l.elevation_deg == Approx(0.0).margin(1e-6));
            CHECK(l.range_m == Approx(1000.0));
        }
    }
    SECTION("up at 30 degrees, north-east") {
        const double r = 5000, el = 30 * deg2rad, az = 45 * deg2rad;
        const Vec3 ned{r * std::cos(el) * std::cos(az), r * std::cos(el) * std::sin(az),
                       -r * std::sin(el)};
        const auto to = target_from_los(hood, ned_to_ecef(ned, hood));
        REQUIRE(to);
        const LookAngles l = look_angles(hood, *to);
        CHECK(l.azimuth_deg == Approx(45.0));
        CHECK(l.elevation_deg == Approx(30.0));
        CHECK(l.range_m == Approx(5000.0));
    }
    SECTION("a point to itself") {
        const LookAngles l = look_angles(hood, hood);
        CHECK(l.range_m == 0.0);
        CHECK(l.azimuth_deg == 0.0);
        CHECK(l.elevation_deg == 0.0);
    }
}

TEST_CASE("MSL altitude is ellipsoid altitude minus geoid undulation", "[geo][geoid]") {
    // Off the US west coast the geoid lies ~20 m below the ellipsoid.
    CHECK(msl_from_ellipsoid(1500.0, -20.0) == 1520.0);
    CHECK(msl_from_ellipsoid(100.0, 30.0) == 70.0);
    CHECK(ellipsoid_from_msl(msl_from_ellipsoid(1234.5, -17.25), -17.25) == 1234.5);
}
