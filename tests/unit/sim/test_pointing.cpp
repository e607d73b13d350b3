#include <catch2/catch.hpp>

#include "sim/pointing.hpp"

using namespace gimbal::sim;

TEST_CASE("pan and tilt turn the line of sight as documented", "[sim][pointing]") {
    const Vec3 ahead = los_in_mount({0, 0});
    CHECK(ahead.x == Approx(1));
    const Vec3 right = los_in_mount({90 * deg, 0});
    CHECK(right.y == Approx(1));
    const Vec3 down = los_in_mount({0, -90 * deg});
    CHECK(down.z == Approx(1));
    const Vec3 up_left = los_in_mount({-90 * deg, 30 * deg});
    CHECK(up_left.y < 0);
    CHECK(up_left.z < 0);
}

TEST_CASE("pan_tilt_for inverts los_in_mount", "[sim][pointing]") {
    for (double pan = -170; pan <= 170; pan += 34)
        for (double tilt = -85; tilt <= 85; tilt += 17) {
            const PanTilt a{pan * deg, tilt * deg};
            const PanTilt b = pan_tilt_for(3.5 * los_in_mount(a));
            CHECK(b.pan == Approx(a.pan).margin(1e-9));
            CHECK(b.tilt == Approx(a.tilt).margin(1e-9));
        }
    CHECK(pan_tilt_for({0, 0, 2}).tilt == Approx(-pi / 2));  // straight down: pan stays 0
    CHECK(pan_tilt_for({0, 0, 2}).pan == 0);
}

TEST_CASE("axes slew at their rate limit and stop on target", "[sim][pointing]") {
    AxisLimits limits;
    limits.pan_rate_max = 30 * deg;
    limits.tilt_rate_max = 10 * deg;
    GimbalAxes axes(limits);
    const PanTilt target{90 * deg, -45 * deg};
    const double dt = 0.01;
    for (int i = 0; i < 100; ++i) axes.slew_toward(target, dt);  // one second
    CHECK(axes.angles().pan == Approx(30 * deg).margin(1e-9));
    CHECK(axes.angles().tilt == Approx(-10 * deg).margin(1e-9));
    CHECK(axes.rates().pan == Approx(30 * deg).margin(1e-9));

    for (int i = 0; i < 500; ++i) axes.slew_toward(target, dt);  // six seconds in all
    CHECK(axes.angles().pan == Approx(90 * deg).margin(1e-9));
    CHECK(axes.angles().tilt == Approx(-45 * deg).margin(1e-9));
    CHECK(axes.rates().pan == Approx(0).margin(1e-9));
}

TEST_CASE("pan takes the shorter way across +-180 degrees", "[sim][pointing]") {
    GimbalAxes axes(AxisLimits{}, {170 * deg, 0});
    axes.slew_toward({-170 * deg, 0}, 1.0);  // 20 degrees to go, 60 deg/s allowed
    CHECK(axes.angles().pan == Approx(-170 * deg).margin(1e-9));
    CHECK(axes.rates().pan == Approx(20 * deg).margin(1e-9));  // turned right, through 180
}

TEST_CASE("tilt stays inside its limits unless told otherwise", "[sim][pointing]") {
    AxisLimits limits;
    limits.tilt_min = -90 * deg;
    limits.tilt_max = 20 * deg;
    GimbalAxes axes(limits);
    for (int i = 0; i < 100; ++i) axes.slew_toward({0, 60 * deg}, 0.1);
    CHECK(axes.angles().tilt == Approx(20 * deg));
    for (int i = 0; i < 100; ++i) axes.move_at(0, -1, 0.1);
    CHECK(axes.angles().tilt == Approx(-90 * deg));
    for (int i = 0; i < 100; ++i) axes.slew_toward({0, -100 * deg}, 0.1, false);
    CHECK(axes.angles().tilt == Approx(-100 * deg));
    axes.slew_toward({0, -100 * deg}, 0.01);  // back within limits at the rate, no jump
    CHECK(axes.angles().tilt == Approx(-100 * deg + 0.6 * deg));
}

TEST_CASE("move_at clamps rates and hold stops the axes", "[sim][pointing]") {
    GimbalAxes axes;
    axes.move_at(10, 0, 0.5);
    CHECK(axes.angles().pan == Approx(30 * deg));
    axes.hold();
    CHECK(axes.rates().pan == 0);
    CHECK(axes.angles().pan == Approx(30 * deg));
}
