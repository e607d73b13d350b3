// VehicleState: which messages it takes (system id filter, first autopilot), freshness and
// its connect/loss reports, flying, time and the STATE object.
#include <catch2/catch.hpp>
#include <cmath>

#include "mavlink/mavlink.hpp"
#include "vehicle/vehicle_state.hpp"
#include "vehicle_fixtures.hpp"

using namespace gimbal;
using vehicle::VehicleOptions;
using vehicle::VehicleState;

namespace {

using vehicle_fixtures::from;
using vehicle_fixtures::options;

mavlink::Heartbeat autopilot_heartbeat(bool armed, mavlink::MavState state) {
    mavlink::Heartbeat hb;
    hb.type = 2;       // quadrotor
    hb.autopilot = 3;  // ArduPilot
    hb.base_mode = armed ? mavlink::mav_mode_flag_safety_armed : 0;
    hb.system_status = static_cast<std::uint8_t>(state);
    return hb;
}

mavlink::Heartbeat gcs_heartbeat() {
    mavlink::Heartbeat hb;
    hb.type = mavlink::mav_type_gcs;
    hb.autopilot = mavlink::mav_autopilot_invalid;
    return hb;
}

mavlink::GlobalPositionInt position(double lat, double lon, double alt_m, double rel_m) {
    mavlink::GlobalPositionInt p;
    p.lat = static_cast<std::int32_t>(std::lround(lat * 1e7));
    p.lon = static_cast<std::int32_t>(std::lround(lon * 1e7));
    p.alt = static_cast<std::int32_t>(std::lround(alt_m * 1000));
    p.relative_alt = static_cast<std::int32_t>(std::lround(rel_m * 1000));
    p.vx = 1250;
    p.vy = -300;
    p.vz = 45;
    p.hdg = 9000;
    return p;
}

}  // namespace

TEST_CASE("without a system id the first autopilot heartbeat picks the vehicle") {
    VehicleState v(options());
    CHECK_FALSE(v.apply(from(7, position(1, 2, 3, 4)), 0.0));  // before any heartbeat
    CHECK_FALSE(v.apply(from(255, gcs_heartbeat()), 0.1));     // a GCS is not a vehicle
    CHECK_FALSE(v.system_id());
    CHECK(v.apply(from(7, autopilot_heartbeat(false, mavlink::MavState::standby)), 0.2));
    REQUIRE(v.system_id());
    CHECK(*v.system_id() == 7);
    CHECK(v.apply(from(7, position(1, 2, 3, 4)), 0.3));
    CHECK_FALSE(v.apply(from(8, autopilot_heartbeat(true, mavlink::MavState::active)), 0.4));
    CHECK_FALSE(v.apply(from(8, position(5, 6, 7, 8)), 0.4));
    REQUIRE(v.position());
    CHECK(v.position()->message.lat == 10000000);
    CHECK(v.messages() == 2);
    CHECK(v.ignored() == 4);
}

TEST_CASE("a configured system id takes only that system, and no camera heartbeat") {
    VehicleState v(options(3));
    CHECK_FALSE(v.apply(from(1, autopilot_heartbeat(true, mavlink::MavState::active)), 0.0));
    CHECK(v.apply(from(3, position(1, 2, 3, 4)), 0.1));  // no heartbeat needed
    mavlink::Heartbeat camera = autopilot_heartbeat(false, mavlink::MavState::active);
    camera.autopilot = mavlink::mav_autopilot_invalid;
    CHECK_FALSE(v.apply(from(3, camera, 100), 0.2));
    CHECK(v.apply(from(3, autopilot_heartbeat(true, mavlink::MavState::active)), 0.3));
    CHECK(v.flying());
}

TEST_CASE("freshness follows the timeout and changes are reported once") {
    VehicleState v(options());
    CHECK_FALSE(v.fresh(0.0));
    CHECK_FALSE(v.connection_change(0.0));  // starts "not connected": nothing to report
    v.apply(from(1, autopilot_heartbeat(false, mavlink::MavState::standby)), 10.0);
    CHECK(v.fresh(10.5));
    CHECK(v.connection_change(10.5) == std::optional<bool>(true));
    CHECK_FALSE(v.connection_change(10.6));
    CHECK(v.fresh(11.0));
    CHECK_FALSE(v.fresh(11.01));
    CHECK(v.connection_change(11.2) == std::optional<bool>(false));
    CHECK_FALSE(v.connection_change(11.3));
    v.apply(from(1, position(1, 2, 3, 4)), 12.0);
    CHECK(v.connection_change(12.0) == std::optional<bool>(true));
}

TEST_CASE("flying needs armed and a flying MAV_STATE") {
    VehicleState v(options());
    CHECK_FALSE(v.flying());
    using S = mavlink::MavState;
    const struct {
        bool armed;
        S state;
        bool flying;
    } cases[] = {{true, S::active, true},   {true, S::critical, true}, {true, S::emergency, true},
                 {true, S::standby, false}, {false, S::active, false}, {false, S::standby, false},
                 {true, S::poweroff, false}};
    double t = 0;
    for (const auto& c : cases) {
        v.apply(from(1, autopilot_heartbeat(c.armed, c.state)), t += 0.1);
        CHECK(v.flying() == c.flying);
    }
}

TEST_CASE("vehicle time is SYSTEM_TIME advanced by its age, and lost with the timeout") {
    VehicleState v(options());
    v.apply(from(1, autopilot_heartbeat(false, mavlink::MavState::standby)), 0.0);
    CHECK_FALSE(v.unix_time_s(0.0));
    mavlink::SystemTime st;
    st.time_unix_usec = 0;  // the autopilot has no time yet
    v.apply(from(1, st), 1.0);
    CHECK_FALSE(v.unix_time_s(1.0));
    st.time_unix_usec = 1'700'000'000'250'000ULL;
    v.apply(from(1, st), 2.0);
    REQUIRE(v.unix_time_s(2.5));
    CHECK(*v.unix_time_s(2.5) == Approx(1'700'000'000.75).margin(1e-6));
    CHECK_FALSE(v.unix_time_s(3.5));
}

TEST_CASE("the STATE object shows the vehicle in contract units") {
    VehicleState v(options(std::nullopt, 1.0, "udp 127.0.0.1:14550"));
    auto empty = v.snapshot(0.0);
    CHECK(empty["source"] == "udp 127.0.0.1:14550");
    CHECK(empty["connected"] == false);
    CHECK(empty["age_s"].is_null());
    CHECK(empty["attitude"].is_null());
    CHECK(empty["position"].is_null());
    CHECK(empty["armed"].is_null());

    v.apply(from(1, autopilot_heartbeat(true, mavlink::MavState::active)), 1.0);
    mavlink::Attitude a;
    a.roll = 0.1f;
    a.pitch = -0.2f;
    a.yaw = 1.5f;
    v.apply(from(1, a), 1.0);
    v.apply(from(1, position(45.5, -122.25, 812.5, 120.25)), 1.2);
    mavlink::SystemTime st;
    st.time_unix_usec = 1'767'225'600'000'000ULL;  // 2026-01-01T00:00:00Z
    v.apply(from(1, st), 1.2);

    const auto s = v.snapshot(1.5);
    CHECK(s["connected"] == true);
    CHECK(s["system_id"] == 1);
    CHECK(s["age_s"].get<double>() == Approx(0.3));
    CHECK(s["attitude"]["roll"].get<double>() == Approx(0.1 * 180 / M_PI).margin(1e-3));
    CHECK(s["attitude"]["pitch"].get<double>() == Approx(-0.2 * 180 / M_PI).margin(1e-3));
    CHECK(s["attitude"]["yaw"].get<double>() == Approx(1.5 * 180 / M_PI).margin(1e-3));
    CHECK(s["position"]["lat"].get<double>() == Approx(45.5));
    CHECK(s["position"]["lon"].get<double>() == Approx(-122.25));
    CHECK(s["position"]["alt_msl"].get<double>() == Approx(812.5));
    CHECK(s["relative_alt"].get<double>() == Approx(120.25));
    CHECK(s["velocity_ned"][0].get<double>() == Approx(12.5));
    CHECK(s["velocity_ned"][1].get<double>() == Approx(-3.0));
    CHECK(s["velocity_ned"][2].get<double>() == Approx(0.45));
    CHECK(s["heading"].get<double>() == Approx(90.0));
    CHECK(s["armed"] == true);
    CHECK(s["flying"] == true);
    CHECK(s["system_status"] == "active");
    CHECK(s["time"] == "2026-01-01T00:00:00Z");

    const auto lost = v.snapshot(5.0);
    CHECK(lost["connected"] == false);
    CHECK(lost["time"].is_null());
    CHECK(lost["position"]["lat"].get<double>() == Approx(45.5));  // last known, with its age
    CHECK(lost["position"]["age_s"].get<double>() == Approx(3.8));
}
