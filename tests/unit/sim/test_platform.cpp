#include <catch2/catch.hpp>

#include "sim/platform.hpp"

using namespace gimbal::sim;

TEST_CASE("the platform flies the configured circle", "[sim][platform]") {
    CircleOptions o;
    o.radius_m = 1000;
    o.speed_mps = 25;
    const CirclePlatform circle(o);
    const Vec3 centre = to_ecef(o.centre);
    const Mat3 ned = transpose(ned_to_ecef(o.centre.lat, o.centre.lon));
    const double period = 2 * pi * 1000 / 25;

    for (double t = 0; t < period; t += period / 17) {
        const PlatformState s = circle.at(t);
        const Vec3 offset = ned * (s.ecef - centre);
        CHECK(std::hypot(offset.x, offset.y) == Approx(1000).margin(0.5));
        CHECK(s.lla.alt == Approx(1500).margin(1e-6));
        CHECK(norm(s.vel_ned) == Approx(25));
        // Velocity along the tangent, heading along the velocity, banked into the turn.
        CHECK(std::abs(dot(s.vel_ned, Vec3{offset.x, offset.y, 0})) < 1e-6 * 25 * 1000);
        CHECK(s.yaw == Approx(std::atan2(s.vel_ned.y, s.vel_ned.x)).margin(1e-9));
        CHECK(s.roll == Approx(std::atan(625 / (9.80665 * 1000))));
    }
    // Clockwise seen from above: from north of the centre it heads east.
    CHECK(circle.at(0).vel_ned.y == Approx(25));
    // Positions over time match the speed.
    const double moved = norm(circle.at(1.0).ecef - circle.at(0).ecef);
    CHECK(moved == Approx(25).epsilon(1e-3));
    CHECK(norm(circle.at(period).ecef - circle.at(0).ecef) < 0.5);
}

TEST_CASE("zero radius hovers at the centre", "[sim][platform]") {
    CircleOptions o;
    o.radius_m = 0;
    const CirclePlatform circle(o);
    const PlatformState s = circle.at(123.0);
    CHECK(norm(s.ecef - to_ecef(o.centre)) < 1e-6);
    CHECK(norm(s.vel_ned) == 0);
    CHECK(s.roll == 0);
}

TEST_CASE("an external fix sets position and heading", "[sim][platform]") {
    const PlatformState s = platform_from_fix({0.8, -2.1, 900}, {0, -20, 0}, 0.3);
    CHECK(s.yaw == Approx(-pi / 2));
    CHECK(to_lla(s.ecef).lat == Approx(0.8));
    const PlatformState slow = platform_from_fix({0.8, -2.1, 900}, {0.1, 0, 0}, 0.3);
    CHECK(slow.yaw == Approx(0.3));
}
