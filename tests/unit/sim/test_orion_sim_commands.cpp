// How the simulated Orion answers commands: OrionCmd, geopoint, path, laser, retract, camera.
#include <algorithm>
#include <catch2/catch.hpp>

#include "protocols/orion/codec/packets.hpp"
#include "sim/frames.hpp"
#include "sim/pointing.hpp"
#include "sim/terrain.hpp"
#include "sim_harness.hpp"

using namespace gimbal;
using namespace sim_test;
namespace pkt = orion::pkt;

namespace {

orion::Cmd command(orion::Mode mode, double pan = 0, double tilt = 0, bool stabilized = false) {
    orion::Cmd c;
    c.cmd.mode = mode;
    c.cmd.target = {pan, tilt};
    c.cmd.stabilized = stabilized;
    return c;
}

bool contains(const Bytes& haystack, const Bytes& needle) {
    return std::search(haystack.begin(), haystack.end(), needle.begin(), needle.end()) !=
           haystack.end();
}

// Line of sight of a telemetry packet, from its attitude and pan/tilt (ECEF, unit).
sim::Vec3 los_from_angles(const orion::GeolocateTelemetry& t) {
    const sim::Quat q{t.quat[0], t.quat[1], t.quat[2], t.quat[3]};
    return sim::mount_to_ecef(q, t.lat, t.lon) * sim::los_in_mount({t.pan, t.tilt});
}

sim::Vec3 position(const orion::GeolocateTelemetry& t) {
    return sim::to_ecef({t.lat, t.lon, t.alt});
}

}  // namespace

TEST_CASE("OrionCmd is echoed back byte for byte", "[sim][orion][cmd]") {
    Harness h;
    h.run(0.5);
    const auto c = command(orion::Mode::rate, 0.05, -0.02, true);
    const Bytes wire = orion::to_wire(c);
    h.send(wire);
    const auto got = h.run(0.001, 0.001);
    REQUIRE(count_id(got, pkt::cmd) == 1);
    CHECK(contains(h.raw(), wire));

    // Commands that cannot be given by OrionCmd are still echoed, but change nothing.
    const Bytes geopoint_mode = orion::to_wire(command(orion::Mode::geopoint));
    h.send(geopoint_mode);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(0.3));
    CHECK(contains(h.raw(), geopoint_mode));
    REQUIRE(!t.empty());
    CHECK(t.back().mode == orion::Mode::rate);
}

TEST_CASE("position commands slew at the rate limit", "[sim][orion][cmd]") {
    sim::OrionSimOptions o;
    o.pan_rate_max_dps = 60;
    o.tilt_rate_max_dps = 20;
    Harness h(o);
    h.run(0);
    h.run(2.0);  // a telemetry tick falls exactly on the command
    h.send_packet(command(orion::Mode::position, 90 * sim::deg, -50 * sim::deg));
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(2.0));
    REQUIRE(t.size() == 20);
    // t[k] is (k + 1) tenths of a second after the command.
    CHECK(t[4].pan == Approx(30 * sim::deg).margin(0.001));    // 0.5 s at 60 deg/s
    CHECK(t[4].tilt == Approx(-40 * sim::deg).margin(0.001));  // from -30, at 20 deg/s
    CHECK(t[9].pan == Approx(60 * sim::deg).margin(0.001));
    CHECK(t[9].tilt == Approx(-50 * sim::deg).margin(0.001));  // arrived after 0.5 s
    CHECK(t[19].pan == Approx(90 * sim::deg).margin(0.001));   // arrived after 1.5 s
    for (const auto& s : t) CHECK(s.mode == orion::Mode::position);
}

TEST_CASE("rate commands turn the axes, and an impulse time stops them", "[sim][orion][cmd]") {
    Harness h;
    h.run(0);
    h.run(1.0);
    auto c = command(orion::Mode::rate, 10 * sim::deg, 0);
    c.cmd.impulse_time_s = 0.5;
    h.send_packet(c);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(2.0));
    REQUIRE(t.size() == 20);
    CHECK(t[1].pan == Approx(2 * sim::deg).margin(0.001));
    CHECK(t[19].pan == Approx(5 * sim::deg).margin(0.001));
    CHECK(t[19].mode == orion::Mode::rate);
}

TEST_CASE("the mode of an OrionCmd with zero targets is reported in telemetry",
          "[sim][orion][cmd]") {
    Harness h;
    h.run(0.2);
    for (const auto mode :
         {orion::Mode::disabled, orion::Mode::ffc_auto, orion::Mode::ffc_manual, orion::Mode::scene,
          orion::Mode::track, orion::Mode::calibration, orion::Mode::geo_rate, orion::Mode::rate,
          orion::Mode::position, orion::Mode::position_no_limits}) {
        h.send_packet(command(mode));
        const auto t = decoded<orion::GeolocateTelemetry>(h.run(0.25));
        REQUIRE(!t.empty());
        INFO("mode " << orion::enum_name(mode));
        CHECK(t.back().mode == mode);
    }
}

TEST_CASE("disabled motors hold the axes where they are", "[sim][orion][cmd]") {
    Harness h;
    h.run(0.1);
    h.send_packet(command(orion::Mode::position, 1.0, -0.5));
    h.run(0.5);
    h.send_packet(command(orion::Mode::disabled));
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(2.0));
    REQUIRE(t.size() > 10);
    CHECK(t.front().pan == Approx(t.back().pan).margin(1e-4));
    CHECK(t.back().pan < 1.0);
}

TEST_CASE("geopoint turns the line of sight onto the commanded point", "[sim][orion][geopoint]") {
    Harness h;
    h.run(1.0);
    orion::GeopointCmd g;
    g.target_lat = 45.712 * sim::deg;
    g.target_lon = -121.47 * sim::deg;
    g.target_alt = sim::terrain_height(45.712, -121.47);  // on the simulator's terrain
    h.send_packet(g);
    const sim::Vec3 target = sim::to_ecef({g.target_lat, g.target_lon, g.target_alt});

    h.run(5.0);  // at most 180 degrees at 60 deg/s, then tracking
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(20.0));
    REQUIRE(t.size() == 200);
    for (const auto& s : t) {
        CHECK(s.mode == orion::Mode::geopoint);
        const sim::Vec3 wanted = target - position(s);
        const sim::Vec3 los{s.los_ecef[0], s.los_ecef[1], s.los_ecef[2]};
        CHECK(sim::angle_between(los, wanted) < 0.1 * sim::deg);
        CHECK(sim::angle_between(los_from_angles(s), wanted) < 0.05 * sim::deg);
        // The line of sight ends on the point (the point is on the terrain).
        CHECK(norm(position(s) + los - target) < 5.0);
    }

    // An OrionCmd cancels geopoint.
    h.send_packet(command(orion::Mode::rate));
    const auto after = decoded<orion::GeolocateTelemetry>(h.run(0.3));
    REQUIRE(!after.empty());
    CHECK(after.back().mode == orion::Mode::rate);
}

TEST_CASE("a moving geopoint is followed, and the stare option sends one StareStart",
          "[sim][orion][geopoint]") {
    Harness h;
    h.run(0.5);
    orion::GeopointCmd g;
    g.target_lat = 45.69 * sim::deg;
    g.target_lon = -121.5 * sim::deg;
    g.target_alt = 100;
    g.target_vel_ned = {0, 20, 0};  // eastward at 20 m/s
    g.options = orion::GeopointOptions::stare;
    h.send_packet(g);
    const auto frames = h.run(10.0);
    CHECK(count_id(frames, pkt::stare_start) == 1);
    const auto t = decoded<orion::GeolocateTelemetry>(frames);
    REQUIRE(!t.empty());
    const auto& last = t.back();
    const sim::Vec3 start = sim::to_ecef({g.target_lat, g.target_lon, g.target_alt});
    const sim::Vec3 moved =
        start + sim::ned_to_ecef(g.target_lat, g.target_lon) * sim::Vec3{0, 20 * 10.0, 0};
    const sim::Vec3 los{last.los_ecef[0], last.los_ecef[1], last.los_ecef[2]};
    CHECK(sim::angle_between(los, moved - position(last)) < 0.2 * sim::deg);
}

TEST_CASE("path mode sweeps the path and reports its progress", "[sim][orion][path]") {
    Harness h;
    h.run(0.5);
    orion::Path p;
    std::vector<sim::Vec3> points;
    for (double lon : {-121.51, -121.49, -121.47}) {
        const sim::Vec3 e = sim::to_ecef({45.69 * sim::deg, lon * sim::deg, 100});
        points.push_back({std::round(e.x), std::round(e.y), std::round(e.z)});
        p.points.push_back({{points.back().x, points.back().y, points.back().z}});
    }
    const double length = norm(points[1] - points[0]) + norm(points[2] - points[1]);
    h.send_packet(p);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(60.0));
    REQUIRE(t.size() == 600);
    double last = -1;
    bool saw_second_segment = false;
    for (const auto& s : t) {
        CHECK(s.mode == orion::Mode::path);
        CHECK(s.path_progress >= last - 1e-9);
        last = s.path_progress;
        saw_second_segment |= s.path_from == 1 && s.path_to == 2;
    }
    // t[k] is 0.1 (k + 1) s after the command; the look point moves at 100 m/s.
    CHECK(t[100].path_progress == Approx(100 * 10.1 / length).margin(0.005));
    CHECK(saw_second_segment);
    CHECK(t.back().path_progress == Approx(1.0));
}

TEST_CASE("step-stare sends StareStart and moves on after StareAck", "[sim][orion][path]") {
    auto run_path = [](bool acknowledge) {
        Harness h;
        h.run(0.5);
        orion::Path p;
        for (double lon : {-121.51, -121.45}) {
            const sim::Vec3 e = sim::to_ecef({45.69 * sim::deg, lon * sim::deg, 100});
            p.points.push_back({{std::round(e.x), std::round(e.y), std::round(e.z)}});
        }
        p.along_track_step_angle = 5 * sim::deg;
        h.send_packet(p);
        std::vector<orion::StareStart> stares;
        bool saw_stare_time = false;
        for (int i = 0; i < 200; ++i) {  // 20 s
            const auto frames = h.run(0.1);
            for (const auto& s : decoded<orion::StareStart>(frames)) {
                stares.push_back(s);
                if (acknowledge) h.send_packet(orion::StareAck{s.system_time_ms});
            }
            for (const auto& t : decoded<orion::GeolocateTelemetry>(frames))
                saw_stare_time |= t.stare_time_s > 0;
        }
        if (!acknowledge) CHECK(saw_stare_time);
        return stares;
    };

    const auto unacked = run_path(false);
    const auto acked = run_path(true);
    REQUIRE(unacked.size() >= 3);
    CHECK(acked.size() > unacked.size());  // an ack ends the 1 s stare at once
    CHECK_FALSE(unacked[0].prev_stare_terminated_by_time);
    CHECK(unacked[1].prev_stare_terminated_by_time);
    CHECK_FALSE(acked[1].prev_stare_terminated_by_time);
    CHECK(acked[0].along_track_stare);
    CHECK(acked[0].gimbal_data_valid);
    CHECK(acked[0].max_stare_time_s == Approx(1.0).margin(0.01));
    CHECK(acked[1].system_time_ms > acked[0].system_time_ms);
    // The first stare is at the first path point.
    CHECK(acked[0].lon == Approx(-121.51 * sim::deg).margin(1e-6));
    CHECK(acked[0].alt == Approx(100).margin(1.0));
}

TEST_CASE("a wrong StareAck does not end the stare", "[sim][orion][path]") {
    Harness h;
    h.run(0.5);
    orion::Path p;
    const sim::Vec3 e = sim::to_ecef({45.69 * sim::deg, -121.5 * sim::deg, 100});
    p.points.push_back({{std::round(e.x), std::round(e.y), std::round(e.z)}});
    p.points.push_back({{std::round(e.x) + 3000, std::round(e.y), std::round(e.z)}});
    p.along_track_step_angle = 5 * sim::deg;
    h.send_packet(p);
    std::vector<orion::StareStart> stares;
    for (int i = 0; i < 100 && stares.empty(); ++i) stares = decoded<orion::StareStart>(h.run(0.1));
    REQUIRE(stares.size() == 1);
    h.send_packet(orion::StareAck{stares[0].system_time_ms + 1});
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(0.5));
    REQUIRE(!t.empty());
    CHECK(t.back().stare_time_s > 0.3);
}

TEST_CASE("path with pointDown and no points looks straight down", "[sim][orion][path]") {
    Harness h;
    h.run(0.5);
    orion::Path p;
    p.point_down = true;
    h.send_packet(p);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(5.0));
    REQUIRE(!t.empty());
    const auto& s = t.back();
    CHECK(s.mode == orion::Mode::down);
    const sim::Vec3 los{s.los_ecef[0], s.los_ecef[1], s.los_ecef[2]};
    // Straight down onto the simulator's terrain.
    CHECK(norm(los) ==
          Approx(s.alt - sim::terrain_height(s.lat / sim::deg, s.lon / sim::deg)).margin(2));
}

TEST_CASE("the laser states packet answers each laser command", "[sim][orion][laser]") {
    Harness h;
    h.run(0.5);
    orion::LaserCmd c;
    c.enable = true;
    c.fire = true;  // not armed
    h.send_packet(c);
    auto states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    REQUIRE(states[0].states.size() == 2);
    CHECK(states[0].states[0].type == orion::LaserType::pointer);
    CHECK(states[0].states[0].enabled);
    CHECK_FALSE(states[0].states[0].armed);
    CHECK_FALSE(states[0].states[0].active);

    c.arm = true;
    h.send_packet(c);
    states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    CHECK(states[0].states[0].active);
    CHECK_FALSE(states[0].states[1].active);

    c.fire = false;
    h.send_packet(c);
    states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    CHECK_FALSE(states[0].states[0].active);
    CHECK(states[0].states[0].armed);
}

TEST_CASE("a configured laser password must be given", "[sim][orion][laser]") {
    sim::OrionSimOptions o;
    o.laser_password = "hunter2";
    Harness h(o);
    h.run(0.5);
    orion::LaserCmd c;
    c.index = 1;
    c.enable = c.arm = c.fire = true;
    h.send_packet(c);
    auto states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    CHECK(states[0].states[1].password_lock);
    CHECK_FALSE(states[0].states[1].active);
    c.password = "hunter2";
    h.send_packet(c);
    states = decoded<orion::LaserStates>(h.run(0.001, 0.001));
    REQUIRE(states.size() == 1);
    CHECK(states[0].states[1].active);
    CHECK_FALSE(states[0].states[1].password_lock);
}

TEST_CASE("retract commands are answered and the arm moves", "[sim][orion][retract]") {
    Harness h;
    h.run(0.5);
    h.send_packet(orion::RetractCommand{orion::RetractCmd::retract});
    auto status = decoded<orion::RetractStatus>(h.run(0.001, 0.001));
    REQUIRE(status.size() == 1);
    CHECK(status[0].state == orion::RetractState::retracting);
    CHECK(status[0].cmd == orion::RetractCmd::retract);
    status = decoded<orion::RetractStatus>(h.run(5.0));
    REQUIRE(!status.empty());
    CHECK(status.back().state == orion::RetractState::retracted);
    CHECK(status.back().pos > 1.0);
}

TEST_CASE("camera switch and zoom change the reported field of view", "[sim][orion][camera]") {
    Harness h;
    h.run(0.5);
    auto t = decoded<orion::GeolocateTelemetry>(h.run(0.2));
    REQUIRE(!t.empty());
    const double wide = t.back().hfov;

    orion::CameraState zoom;
    zoom.zoom = 4;
    h.send_packet(zoom);
    t = decoded<orion::GeolocateTelemetry>(h.run(0.2));
    REQUIRE(!t.empty());
    CHECK(std::tan(t.back().hfov / 2) == Approx(std::tan(wide / 2) / 4).epsilon(0.01));

    h.send_packet(orion::CameraSwitch{1});
    t = decoded<orion::GeolocateTelemetry>(h.run(0.2));
    REQUIRE(!t.empty());
    CHECK(t.back().pixel_width == 640);
    CHECK(t.back().pixel_height == 512);

    h.send_packet(orion::CameraSwitch{7});  // no such camera: ignored
    t = decoded<orion::GeolocateTelemetry>(h.run(0.2));
    CHECK(t.back().pixel_width == 640);
}

TEST_CASE("range data replaces the terrain range while it is fresh", "[sim][orion][range]") {
    Harness h;
    h.run(0.5);
    orion::RangeData r;
    r.range_m = 800;
    r.max_age_ms = 1000;
    r.source = orion::RangeSource::laser;
    h.send_packet(r);
    auto t = decoded<orion::GeolocateTelemetry>(h.run(0.5));
    REQUIRE(!t.empty());
    const auto& s = t.back();
    CHECK(s.range_source == orion::RangeSource::laser);
    CHECK(std::hypot(s.los_ecef[0], s.los_ecef[1], s.los_ecef[2]) == Approx(800).margin(1.5));
    t = decoded<orion::GeolocateTelemetry>(h.run(1.0));
    CHECK(t.back().range_source == orion::RangeSource::internal);
}

TEST_CASE("GPS data sent to the gimbal overrides its position", "[sim][orion][gps]") {
    Harness h;
    h.run(0.5);
    orion::GpsData g;
    g.lat = 46.0 * sim::deg;
    g.lon = -122.0 * sim::deg;
    g.alt = 900;
    g.vel_ned = {10, 0, 0};
    g.fix_type = orion::UbloxFixType::three_d_fix;
    h.send_packet(g);
    const auto frames = h.run(1.0);
    const auto t = decoded<orion::GeolocateTelemetry>(frames);
    REQUIRE(!t.empty());
    CHECK(t.back().lat > 46.0 * sim::deg);  // moving north from the fix
    CHECK(t.back().lat == Approx(46.0 * sim::deg + 10.0 / 6.37e6).margin(2e-7));
    CHECK(t.back().lon == Approx(-122.0 * sim::deg).margin(1e-7));
    const auto ins = decoded<orion::InsQuality>(frames);
    REQUIRE(!ins.empty());
    CHECK(ins.back().gps_source == orion::GpsSource::external);

    // Without more fixes the gimbal goes back to its own GPS (the circle).
    const auto later = decoded<orion::GeolocateTelemetry>(h.run(3.0));
    CHECK(later.back().lat == Approx(45.7 * sim::deg).margin(0.001));
}
