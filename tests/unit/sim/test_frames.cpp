#include <catch2/catch.hpp>

#include "sim/frames.hpp"

using namespace gimbal::sim;

TEST_CASE("geodetic and ECEF positions convert both ways", "[sim][frames]") {
    const Lla p{45.7 * deg, -121.5 * deg, 1500};
    const Vec3 e = to_ecef(p);
    CHECK(norm(e) == Approx(6367489.5 + 1500).margin(2000));  // near the Earth's radius there
    const Lla back = to_lla(e);
    CHECK(back.lat == Approx(p.lat).margin(1e-12));
    CHECK(back.lon == Approx(p.lon).margin(1e-12));
    CHECK(back.alt == Approx(p.alt).margin(1e-6));
}

TEST_CASE("local NED axes point north, east and down", "[sim][frames]") {
    const Lla p{45.7 * deg, -121.5 * deg, 0};
    const Mat3 r = ned_to_ecef(p.lat, p.lon);
    const Vec3 e = to_ecef(p);
    const Vec3 north = to_ecef({p.lat + 1e-6, p.lon, 0}) - e;
    const Vec3 east = to_ecef({p.lat, p.lon + 1e-6, 0}) - e;
    const Vec3 down = to_ecef({p.lat, p.lon, -1}) - e;
    CHECK(angle_between(r * Vec3{1, 0, 0}, north) < 1e-6);
    CHECK(angle_between(r * Vec3{0, 1, 0}, east) < 1e-6);
    CHECK(angle_between(r * Vec3{0, 0, 1}, down) < 1e-6);
}

TEST_CASE("a body quaternion turns body axes into NED", "[sim][frames]") {
    const Mat3 r = dcm_from_quat(quat_from_euler(0, 0, 90 * deg));  // heading east
    const Vec3 forward = r * Vec3{1, 0, 0};
    CHECK(forward.x == Approx(0).margin(1e-12));
    CHECK(forward.y == Approx(1));
    const Mat3 nose_down = dcm_from_quat(quat_from_euler(0, -90 * deg, 0));
    CHECK((nose_down * Vec3{1, 0, 0}).z == Approx(1));
}

TEST_CASE("a ray meets flat terrain at the terrain height", "[sim][frames]") {
    const Lla above{45.7 * deg, -121.5 * deg, 1500};
    const Vec3 origin = to_ecef(above);
    const Mat3 ned = ned_to_ecef(above.lat, above.lon);

    SECTION("straight down: the range is the height above the terrain") {
        const auto hit = hit_flat_terrain(origin, ned * Vec3{0, 0, 1}, 100);
        REQUIRE(hit);
        CHECK(norm(*hit - origin) == Approx(1400).margin(1e-3));
        CHECK(to_lla(*hit).alt == Approx(100).margin(1e-3));
    }
    SECTION("45 degrees down, north: the hit is on the terrain, about 1400 m ahead") {
        const auto hit = hit_flat_terrain(origin, ned * Vec3{1, 0, 1}, 100);
        REQUIRE(hit);
        const Lla g = to_lla(*hit);
        CHECK(g.alt == Approx(100).margin(1e-3));
        CHECK(g.lat > above.lat);
        CHECK(norm(*hit - origin) == Approx(1400 * std::sqrt(2.0)).epsilon(0.01));
    }
    SECTION("level or upward rays and rays from below the terrain miss") {
        CHECK_FALSE(hit_flat_terrain(origin, ned * Vec3{0, 0, -1}, 100));
        CHECK_FALSE(hit_flat_terrain(origin, ned * Vec3{1, 0, -0.01}, 100));
        CHECK_FALSE(hit_flat_terrain(origin, ned * Vec3{0, 0, 1}, 2000));
        CHECK_FALSE(hit_flat_terrain(origin, Vec3{}, 100));
    }
}

TEST_CASE("angles wrap into -pi up to pi", "[sim][frames]") {
    CHECK(wrap_pi(0) == Approx(0));
    CHECK(wrap_pi(3 * pi / 2) == Approx(-pi / 2));
    CHECK(wrap_pi(-3 * pi / 2) == Approx(pi / 2));
    CHECK(wrap_pi(pi) == Approx(-pi));
    CHECK(wrap_pi(7 * pi + 0.1) == Approx(-pi + 0.1));
}
