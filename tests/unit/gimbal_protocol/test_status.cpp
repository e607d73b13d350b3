// A gimbal's typed state -> GIMBAL_DEVICE_ATTITUDE_STATUS, CAMERA_FOV_STATUS,
// GIMBAL_MANAGER_STATUS, HEARTBEAT.
#include <catch2/catch.hpp>

#include "fixtures.hpp"
#include "geo/attitude.hpp"

using namespace gptest;

namespace {

gimbal::geo::EulerDeg euler_of(const std::array<float, 4>& q) {
    return gimbal::geo::quat_to_euler(gimbal::geo::Quat{q[0], q[1], q[2], q[3]});
}

}  // namespace

TEST_CASE("HEARTBEAT of a gimbal component") {
    const auto hb = heartbeat();
    CHECK(hb.type == 26);
    CHECK(hb.autopilot == 8);
    CHECK(hb.mavlink_version == 3);
}

TEST_CASE("line of sight: mount attitude, then pan, then tilt, in NED") {
    const auto g = two_gimbals();
    auto s = orion_state();
    SECTION("level mount: yaw = pan, pitch = tilt") {
        const auto st = attitude_status(g[0], s, 99);
        const auto e = euler_of(st.q);
        CHECK(e.yaw_deg == Approx(30).margin(1e-3));
        CHECK(e.pitch_deg == Approx(-20).margin(1e-3));
        CHECK(e.roll_deg == Approx(0).margin(1e-3));
        CHECK(st.gimbal_device_id == 1);
        CHECK(st.time_boot_ms == 99);
        CHECK((st.flags & mav::gimbal_flags::yaw_in_earth_frame) != 0);
        CHECK(st.failure_flags == 0);
    }
    SECTION("mount yawed 90 degrees (aircraft heading east): line of sight yaw 120") {
        s->set_quat(gimbal::geo::euler_to_quat(gimbal::geo::EulerDeg{0, 0, 90}));
        const auto e = euler_of(attitude_status(g[0], s, 0).q);
        CHECK(e.yaw_deg == Approx(120).margin(1e-3));
        CHECK(e.pitch_deg == Approx(-20).margin(1e-3));
    }
    SECTION("mount pitched up 10 degrees, pan 0: pitch adds") {
        s->set_quat(gimbal::geo::euler_to_quat(gimbal::geo::EulerDeg{0, 10, 0}));
        s->shared().pan = 0.0;
        const auto e = euler_of(attitude_status(g[0], s, 0).q);
        CHECK(e.pitch_deg == Approx(-10).margin(1e-3));
        CHECK(e.yaw_deg == Approx(0).margin(1e-3));
    }
    SECTION("Viewpro: aircraft attitude then gimbal angles") {
        const auto e = euler_of(attitude_status(g[1], viewpro_state(), 0).q);
        CHECK(e.yaw_deg == Approx(100).margin(1e-3));
        CHECK(e.pitch_deg == Approx(-45).margin(1e-3));
    }
    SECTION("link down or stale: comms failure flag; no telemetry: NaN quaternion") {
        s->connected = false;
        CHECK((attitude_status(g[0], s, 0).failure_flags & mav::gimbal_error::comms_error) != 0);
        s = orion_state();
        s->stale = true;
        CHECK((attitude_status(g[0], s, 0).failure_flags & mav::gimbal_error::comms_error) != 0);
        s = orion_state();
        s->data.telemetry.reset();
        const auto st = attitude_status(g[0], s, 0);
        for (const float c : st.q) CHECK(std::isnan(c));
        s = orion_state();
        s->shared().pan.reset();  // not a number
        CHECK(std::isnan(attitude_status(g[0], s, 0).q[0]));
    }
}

TEST_CASE("CAMERA_FOV_STATUS: position, image centre (MSL), fovs; unknown as INT32_MAX/NaN") {
    const auto g = two_gimbals();
    const auto f = fov_status(g[0], orion_state(), 5);
    CHECK(f.lat_camera == 450000000);
    CHECK(f.lon_camera == -1210000000);
    CHECK(f.alt_camera == 1521000);
    CHECK(f.lat_image == 450100000);
    CHECK(f.alt_image == 100000);  // 79 m WGS84 + 21 m
    CHECK(f.hfov == 40.0f);
    CHECK(f.vfov == 30.0f);
    CHECK(f.camera_device_id == 1);
    CHECK(euler_of(f.q).yaw_deg == Approx(30).margin(1e-3));

    auto s = orion_state();
    s->shared().target.reset();
    s->shared().hfov.reset();
    const auto u = fov_status(g[0], s, 5);
    CHECK(u.lat_image == mav::CameraFovStatus::unknown);
    CHECK(u.alt_image == mav::CameraFovStatus::unknown);
    CHECK(std::isnan(u.hfov));

    const auto v = fov_status(g[1], viewpro_state(), 5);
    CHECK(v.lat_camera == 69400000);
    CHECK(v.alt_camera == 300000);
    CHECK(v.lat_image == 69450000);
    CHECK(v.alt_image == mav::CameraFovStatus::unknown);  // OUT3 carries no target altitude
    CHECK(std::isnan(v.hfov));

    const auto empty = fov_status(g[0], gimbal::session::GimbalView{}, 5);
    CHECK(empty.lat_camera == mav::CameraFovStatus::unknown);
    CHECK(std::isnan(empty.q[0]));
}

TEST_CASE("GIMBAL_MANAGER_STATUS carries primary and secondary control") {
    const auto g = two_gimbals();
    Control c;
    auto s = manager_status(g[1], c, 7);
    CHECK(s.gimbal_device_id == 2);
    CHECK(s.primary_control_sysid == 0);
    REQUIRE(c.configure(gcs, -2, -2, 254, 1) == MavResult::accepted);
    s = manager_status(g[1], c, 7);
    CHECK(s.primary_control_sysid == 255);
    CHECK(s.primary_control_compid == 190);
    CHECK(s.secondary_control_sysid == 254);
    CHECK(s.secondary_control_compid == 1);
}
