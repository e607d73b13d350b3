#include <catch2/catch.hpp>

#include "sim/path_follower.hpp"

using namespace gimbal::sim;

namespace {

// A 2 km path running east on flat ground, seen from 1500 m above its start.
struct Scene {
    Lla start{45.7 * deg, -121.5 * deg, 100};
    Vec3 a = to_ecef(start);
    Vec3 b = a + ned_to_ecef(start.lat, start.lon) * Vec3{0, 1000, 0};
    Vec3 c = a + ned_to_ecef(start.lat, start.lon) * Vec3{0, 2000, 0};
    Vec3 gimbal = to_ecef({start.lat, start.lon, 1600});
};

}  // namespace

TEST_CASE("without step-stare the look point sweeps the path at the scan speed", "[sim][path]") {
    Scene s;
    PathOptions o;
    o.scan_speed_mps = 100;
    PathFollower path({s.a, s.b, s.c}, {}, o);
    CHECK(path.progress() == 0);
    CHECK(norm(path.look_point() - s.a) < 1e-6);

    double last = 0;
    for (int i = 0; i < 50; ++i) {  // 5 s
        CHECK_FALSE(path.step(0.1, s.gimbal, 0));
        CHECK(path.progress() >= last);
        last = path.progress();
    }
    CHECK(path.progress() == Approx(0.25).margin(1e-6));
    CHECK(path.from_index() == 0);
    CHECK(path.to_index() == 1);
    CHECK(norm(path.look_point() - s.a) == Approx(500).margin(1e-3));

    for (int i = 0; i < 100; ++i) path.step(0.1, s.gimbal, 0);  // 15 s in all
    CHECK(path.progress() == Approx(0.75).margin(1e-6));
    CHECK(path.from_index() == 1);
    CHECK(path.to_index() == 2);

    for (int i = 0; i < 100; ++i) path.step(0.1, s.gimbal, 0);
    CHECK(path.progress() == 1);
    CHECK(path.finished());
    CHECK(norm(path.look_point() - s.c) < 1e-6);  // it stays at the end
}

TEST_CASE("step-stare waits for the gimbal, stares, and steps by range x angle", "[sim][path]") {
    Scene s;
    PathOptions o;
    o.stare_time_s = 1.0;
    o.step_timeout_s = 2.0;
    o.on_target_rad = 0.5 * deg;
    const double step_angle = 10 * deg;
    PathFollower path({s.a, s.c}, {step_angle, 0, 0}, o);

    // Not on target yet: no stare until the step timeout.
    CHECK_FALSE(path.step(0.5, s.gimbal, 5 * deg));
    CHECK_FALSE(path.staring());

    // On target: the stare starts at once, at the first point.
    auto begin = path.step(0.1, s.gimbal, 0.1 * deg);
    REQUIRE(begin);
    CHECK(begin->along_track);
    CHECK_FALSE(begin->started_by_time);
    CHECK_FALSE(begin->prev_terminated_by_time);
    CHECK(begin->max_stare_time_s == 1.0);
    CHECK(begin->slant_range_m == Approx(1500).margin(0.01));
    CHECK(norm(begin->point_ecef - s.a) < 1e-6);
    CHECK(path.staring());
    CHECK(path.stare_remaining_s() == Approx(1.0));

    path.step(0.3, s.gimbal, 0);
    CHECK(path.stare_remaining_s() == Approx(0.7));

    // StareAck ends it early; the next station is range x step angle further along.
    CHECK(path.acknowledge());
    CHECK_FALSE(path.staring());
    CHECK_FALSE(path.acknowledge());
    CHECK(norm(path.look_point() - s.a) == Approx(1500 * step_angle).margin(1e-3));

    // This time the gimbal never gets there: the stare starts by time.
    CHECK_FALSE(path.step(1.0, s.gimbal, 3 * deg));
    begin = path.step(1.0, s.gimbal, 3 * deg);
    REQUIRE(begin);
    CHECK(begin->started_by_time);
    CHECK(begin->prev_stare_time_s == Approx(0.3));
    CHECK(begin->stare_load == 1.0);

    // No ack: the stare ends when its time runs out, and the next one says so.
    path.step(0.6, s.gimbal, 0);
    CHECK(path.staring());
    path.step(0.6, s.gimbal, 0);
    CHECK_FALSE(path.staring());
    begin = path.step(0.1, s.gimbal, 0);
    REQUIRE(begin);
    CHECK(begin->prev_terminated_by_time);
}

TEST_CASE("step-stare reaches the end of the path and stops", "[sim][path]") {
    Scene s;
    PathFollower path({s.a, s.c}, {30 * deg, 0, 0}, PathOptions{});
    int stares = 0;
    for (int i = 0; i < 1000 && !path.finished(); ++i) {
        if (path.step(0.1, s.gimbal, 0)) {
            ++stares;
            path.acknowledge();
        }
    }
    CHECK(path.finished());
    CHECK(path.progress() == 1);
    // Steps grow with the range; from 1500 m overhead, 30 degree steps cover 2 km in a few.
    CHECK(stares >= 3);
    CHECK(stares <= 6);
}

TEST_CASE("cross-track steps stare left to right across the path", "[sim][path]") {
    Scene s;
    const double step_angle = 4 * deg;
    PathFollower path({s.a, s.c}, {step_angle, 3, 1.0}, PathOptions{});
    std::vector<StareBegin> stares;
    for (int i = 0; i < 200 && stares.size() < 4; ++i) {
        if (auto b = path.step(0.1, s.gimbal, 0)) {
            stares.push_back(*b);
            path.acknowledge();
        }
    }
    REQUIRE(stares.size() == 4);
    CHECK(stares[0].along_track);
    CHECK_FALSE(stares[1].along_track);
    CHECK_FALSE(stares[2].along_track);
    CHECK(stares[3].along_track);  // the next station
    CHECK(stares[0].cross_angle == Approx(-step_angle));
    CHECK(stares[1].cross_angle == Approx(0).margin(1e-12));
    CHECK(stares[2].cross_angle == Approx(step_angle));
    // The path runs east: left of it is north.
    const Mat3 to_ned = transpose(ned_to_ecef(s.start.lat, s.start.lon));
    CHECK((to_ned * (stares[0].point_ecef - s.a)).x > 0);
    CHECK((to_ned * (stares[2].point_ecef - s.a)).x < 0);
}

TEST_CASE("a one-point path looks at the point", "[sim][path]") {
    Scene s;
    PathFollower path({s.b}, {}, PathOptions{});
    path.step(0.1, s.gimbal, 0);
    CHECK(norm(path.look_point() - s.b) < 1e-6);
    CHECK(path.progress() == 1);
    CHECK(path.from_index() == 0);
    CHECK(path.to_index() == 0);
}
