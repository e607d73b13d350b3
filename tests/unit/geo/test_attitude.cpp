// Quaternions [w, x, y, z] (body -> NED) and aerospace ZYX Euler angles.
#include <catch2/catch.hpp>
#include <cmath>

#include "geo/attitude.hpp"

using namespace gimbal::geo;

namespace {

void check_quat(const Quat& got, const Quat& want) {
    // q and -q are the same rotation
    const double sign =
        (got.w * want.w + got.x * want.x + got.y * want.y + got.z * want.z) < 0 ? -1 : 1;
    CHECK(sign * got.w == Approx(want.w).margin(1e-9));
    CHECK(sign * got.x == Approx(want.x).margin(1e-9));
    CHECK(sign * got.y == Approx(want.y).margin(1e-9));
    CHECK(sign * got.z == Approx(want.z).margin(1e-9));
}

void check_vec(const Vec3& got, const Vec3& want) {
    CHECK(got.x == Approx(want.x).margin(1e-12));
    CHECK(got.y == Approx(want.y).margin(1e-12));
    CHECK(got.z == Approx(want.z).margin(1e-12));
}

const double h = std::sqrt(0.5);

}  // namespace

TEST_CASE("quaternions of known roll, pitch and yaw", "[geo][attitude]") {
    check_quat(euler_to_quat(EulerDeg{0, 0, 0}), {1, 0, 0, 0});
    check_quat(euler_to_quat(EulerDeg{90, 0, 0}), {h, h, 0, 0});
    check_quat(euler_to_quat(EulerDeg{0, 90, 0}), {h, 0, h, 0});
    check_quat(euler_to_quat(EulerDeg{0, 0, 90}), {h, 0, 0, h});
    check_quat(euler_to_quat(EulerDeg{0, 0, 180}), {0, 0, 0, 1});
    // The textbook example: roll 10, pitch 20, yaw 30 degrees.
    check_quat(euler_to_quat(EulerDeg{10, 20, 30}),
               {0.9515485246, 0.0381345765, 0.1893078574, 0.2392983377});
    check_quat(euler_to_quat(EulerRad{10 * deg2rad, 20 * deg2rad, 30 * deg2rad}),
               {0.9515485246, 0.0381345765, 0.1893078574, 0.2392983377});
}

TEST_CASE("roll, pitch and yaw of known quaternions", "[geo][attitude]") {
    const EulerDeg e = quat_to_euler({0.9515485246, 0.0381345765, 0.1893078574, 0.2392983377});
    CHECK(e.roll_deg == Approx(10.0).margin(1e-7));
    CHECK(e.pitch_deg == Approx(20.0).margin(1e-7));
    CHECK(e.yaw_deg == Approx(30.0).margin(1e-7));
    const EulerRad r = quat_to_euler_rad({h, 0, 0, -h});
    CHECK(r.roll_rad == Approx(0.0).margin(1e-12));
    CHECK(r.pitch_rad == Approx(0.0).margin(1e-12));
    CHECK(r.yaw_rad == Approx(-pi / 2));
}

TEST_CASE("Euler -> quaternion -> Euler round trip", "[geo][attitude]") {
    for (double roll = -179; roll < 180; roll += 37)
        for (double pitch = -85; pitch <= 85; pitch += 17)
            for (double yaw = -179; yaw < 180; yaw += 41) {
                const EulerDeg e = quat_to_euler(euler_to_quat(EulerDeg{roll, pitch, yaw}));
                CHECK(e.roll_deg == Approx(roll).margin(1e-9));
                CHECK(e.pitch_deg == Approx(pitch).margin(1e-9));
                CHECK(e.yaw_deg == Approx(yaw).margin(1e-9));
            }
}

TEST_CASE("quantised and degenerate quaternions", "[geo][attitude]") {
    // Telemetry carries each component as round(q * 32767) / 32767: not exactly unit length.
    const Quat exact = euler_to_quat(EulerDeg{-5, 12, 250 - 360});
    const Quat quantised{std::round(exact.w * 32767) / 32767, std::round(exact.x * 32767) / 32767,
                         std::round(exact.y * 32767) / 32767, std::round(exact.z * 32767) / 32767};
    const EulerDeg e = quat_to_euler(quantised);
    CHECK(e.roll_deg == Approx(-5).margin(0.01));
    CHECK(e.pitch_deg == Approx(12).margin(0.01));
    CHECK(e.yaw_deg == Approx(-110).margin(0.01));
    // Scale does not matter.
    const EulerDeg doubled = quat_to_euler({2 * exact.w, 2 * exact.x, 2 * exact.y, 2 * exact.z});
    CHECK(doubled.yaw_deg == Approx(-110).margin(1e-9));
    // A zero quaternion (no attitude yet) reads as level, north.
    const EulerDeg zero = quat_to_euler({0, 0, 0, 0});
    CHECK(zero.roll_deg == 0);
    CHECK(zero.pitch_deg == 0);
    CHECK(zero.yaw_deg == 0);
}

TEST_CASE("pitch of +-90 degrees keeps the heading in yaw", "[geo][attitude]") {
    const EulerDeg up = quat_to_euler(euler_to_quat(EulerDeg{0, 90, 40}));
    CHECK(up.pitch_deg == Approx(90));
    CHECK(up.roll_deg == 0);
    CHECK(up.yaw_deg == Approx(40).margin(1e-6));
    // Only yaw - roll is defined looking straight up: the rotation is the same.
    const Quat q = euler_to_quat(EulerDeg{25, 90, 65});
    check_quat(euler_to_quat(quat_to_euler(q)), q);
    const Quat down = euler_to_quat(EulerDeg{10, -90, 30});
    const EulerDeg d = quat_to_euler(down);
    CHECK(d.pitch_deg == Approx(-90));
    check_quat(euler_to_quat(d), down);
}

TEST_CASE("rotating body vectors into NED", "[geo][attitude]") {
    const Vec3 forward{1, 0, 0}, right{0, 1, 0}, down{0, 0, 1};
    check_vec(rotate(euler_to_quat(EulerDeg{0, 0, 90}), forward), {0, 1, 0});   // nose east
    check_vec(rotate(euler_to_quat(EulerDeg{0, 90, 0}), forward), {0, 0, -1});  // nose up
    check_vec(rotate(euler_to_quat(EulerDeg{90, 0, 0}), right), {0, 0, 1});     // right wing down
    check_vec(rotate(euler_to_quat(EulerDeg{0, -30, 0}), forward),
              {std::cos(30 * deg2rad), 0, std::sin(30 * deg2rad)});  // 30 deg nose down
    const Quat q = euler_to_quat(EulerDeg{10, 20, 30});
    const Vec3 v{3, -4, 12};
    check_vec(rotate(conjugate(q), rotate(q, v)), v);
    CHECK(norm(rotate(q, v)) == Approx(13.0));
    // Composition: rotating by a * b is rotating by b, then by a.
    const Quat a = euler_to_quat(EulerDeg{0, 0, 90});
    const Quat b = euler_to_quat(EulerDeg{0, 90, 0});
    check_vec(rotate(a * b, forward), rotate(a, rotate(b, forward)));
    check_vec(rotate(Quat{1, 0, 0, 0}, down), down);
}
