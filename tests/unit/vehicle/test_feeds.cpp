// The feed builders: OrionAutopilotData, GPS_DATA, Viewpro IN1/IN2 and the MAVLink forward,
// each decoded back with the codec of the receiving side.
#include <catch2/catch.hpp>
#include <cmath>

#include "mavlink/mavlink.hpp"
#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/orion_feed_packets.hpp"
#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/viewpro_feed_packets.hpp"
#include "vehicle/feeds.hpp"
#include "vehicle_fixtures.hpp"

using namespace gimbal;
using vehicle::VehicleOptions;
using vehicle::VehicleState;

namespace {

using vehicle_fixtures::from;
using vehicle_fixtures::options;

mavlink::Heartbeat heartbeat(bool armed, mavlink::MavState state) {
    mavlink::Heartbeat hb;
    hb.type = 1;
    hb.autopilot = 12;  // PX4
    hb.base_mode = armed ? mavlink::mav_mode_flag_safety_armed : 0;
    hb.system_status = static_cast<std::uint8_t>(state);
    return hb;
}

mavlink::GlobalPositionInt position() {
    mavlink::GlobalPositionInt p;
    p.time_boot_ms = 123456;
    p.lat = 457000000;
    p.lon = -1215000000;
    p.alt = 1500250;
    p.relative_alt = 350400;
    p.vx = 2000;
    p.vy = -150;
    p.vz = 30;
    p.hdg = 1234;
    return p;
}

mavlink::Attitude attitude() {
    mavlink::Attitude a;
    a.time_boot_ms = 123400;
    a.roll = 0.05f;
    a.pitch = -0.1f;
    a.yaw = 2.0f;
    return a;
}

// A vehicle in flight at t = 10 s, every message just received.
VehicleState flying_vehicle(bool with_time = true) {
    VehicleState v(options());
    v.apply(from(42, heartbeat(true, mavlink::MavState::active), 1), 10.0);
    v.apply(from(42, attitude()), 10.0);
    v.apply(from(42, position()), 10.0);
    if (with_time) {
        mavlink::SystemTime st;
        st.time_unix_usec = 1'767'225'600'000'000ULL;  // 2026-01-01T00:00:00Z
        st.time_boot_ms = 123000;
        v.apply(from(42, st), 10.0);
    }
    return v;
}

}  // namespace

TEST_CASE("AutopilotData: flying, comm good and AGL from the vehicle") {
    auto v = flying_vehicle();
    auto ap = vehicle::orion_autopilot_data(v, 10.5);
    CHECK(ap.is_flying);
    CHECK(ap.comm_good);
    CHECK(ap.agl == 350);
    // Round trip through the Orion codec: four bytes, as the ICD says.
    const auto payload = orion::encode(ap);
    REQUIRE(payload.size == 4);
    const auto back = orion::decode<orion::AutopilotData>(payload.view());
    REQUIRE(back);
    CHECK(back.value.agl == 350);

    // Lost feed: CommGood drops at once, the rest stays the last known.
    ap = vehicle::orion_autopilot_data(v, 11.5);
    CHECK_FALSE(ap.comm_good);
    CHECK(ap.is_flying);

    v.apply(from(42, heartbeat(false, mavlink::MavState::standby)), 12.0);
    ap = vehicle::orion_autopilot_data(v, 12.0);
    CHECK(ap.comm_good);
    CHECK_FALSE(ap.is_flying);
}

TEST_CASE("AutopilotData before any vehicle: not flying, comm bad, AGL invalid") {
    VehicleState v(options());
    const auto ap = vehicle::orion_autopilot_data(v, 0.0);
    CHECK_FALSE(ap.is_flying);
    CHECK_FALSE(ap.comm_good);
    CHECK(ap.agl < 0);
}

TEST_CASE("GPS_DATA from GLOBAL_POSITION_INT, mavlink source, GPS time of SYSTEM_TIME") {
    auto v = flying_vehicle();
    const auto g = vehicle::orion_gps_data(v, 10.25, 0.0);
    REQUIRE(g);
    const auto payload = orion::encode(*g);
    const auto back = orion::decode<orion::GpsData>(payload.view());
    REQUIRE(back);
    CHECK(back.value.source == orion::GpsSource::mavlink);
    CHECK(back.value.fix_type == orion::UbloxFixType::three_d_fix);
    CHECK(back.value.lat * 180 / M_PI == Approx(45.7).margin(1e-6));
    CHECK(back.value.lon * 180 / M_PI == Approx(-121.5).margin(1e-6));
    CHECK(back.value.alt == Approx(1500.25).margin(1e-3));
    CHECK(back.value.vel_ned[0] == Approx(20.0));
    CHECK(back.value.vel_ned[1] == Approx(-1.5));
    CHECK(back.value.vel_ned[2] == Approx(0.3));
    // 2026-01-01T00:00:00Z + 0.25 s is GPS week 2399, Thursday 00:00:18.25.
    CHECK(back.value.week == 2399);
    CHECK(back.value.itow_ms == 4u * 86400000u + 18250u);

    CHECK_FALSE(vehicle::orion_gps_data(v, 11.5, 0.0));  // position too old
}

TEST_CASE("GPS_DATA falls back to the host clock without SYSTEM_TIME") {
    auto v = flying_vehicle(false);
    const auto g = vehicle::orion_gps_data(v, 10.0, 1'767'225'600.0 + 7 * 86400.0);
    REQUIRE(g);
    CHECK(g->week == 2400);
    CHECK(g->itow_ms == 4u * 86400000u + 18000u);
}

TEST_CASE("Viewpro IN2 and IN1 carry the vehicle's attitude, position and time") {
    auto v = flying_vehicle();
    const auto in2 = vehicle::viewpro_in(v, 10.5, 0.0, vehicle::ViewproFrame::in2);
    REQUIRE(in2);
    REQUIRE(in2->size() == viewpro::in2_size);
    const auto frame = viewpro::make_input_frame(*in2);
    REQUIRE(frame);
    CHECK(frame->kind == viewpro::InputFrame::Kind::in2);
    const auto in = viewpro::decode_vehicle(*frame);
    REQUIRE(in);
    CHECK(viewpro::to_iso8601(in->time) == "2026-01-01T00:00:00Z");
    CHECK(in->roll_deg == Approx(0.05 * 180 / M_PI).margin(1e-4));
    CHECK(in->pitch_deg == Approx(-0.1 * 180 / M_PI).margin(1e-4));
    CHECK(in->yaw_deg == Approx(2.0 * 180 / M_PI).margin(1e-4));
    CHECK(in->lat_deg == Approx(45.7).margin(1e-7));
    CHECK(in->lon_deg == Approx(-121.5).margin(1e-7));
    CHECK(in->alt_msl_m == Approx(1500.25).margin(1e-3));
    REQUIRE(in->vel_ned_mps);
    CHECK((*in->vel_ned_mps)[0] == Approx(20.0));
    CHECK((*in->vel_ned_mps)[1] == Approx(-1.5));

    const auto in1 = vehicle::viewpro_in(v, 10.5, 0.0, vehicle::ViewproFrame::in1);
    REQUIRE(in1);
    CHECK(in1->size() == viewpro::in1_size);
    const auto f1 = viewpro::make_input_frame(*in1);
    REQUIRE(f1);
    CHECK(f1->kind == viewpro::InputFrame::Kind::in1);

    CHECK_FALSE(vehicle::viewpro_in(v, 11.5, 0.0, vehicle::ViewproFrame::in2));
}

TEST_CASE("Viewpro frames use the host clock without SYSTEM_TIME") {
    auto v = flying_vehicle(false);
    const auto in2 = vehicle::viewpro_in(v, 10.0, 1'700'000'000.0, vehicle::ViewproFrame::in2);
    REQUIRE(in2);
    const auto in = viewpro::decode_vehicle(*viewpro::make_input_frame(*in2));
    REQUIRE(in);
    CHECK(viewpro::to_iso8601(in->time) == "2023-11-14T22:13:20Z");
}

TEST_CASE("MAVLink forward: v1 frames of ATTITUDE, GLOBAL_POSITION_INT and SYSTEM_TIME") {
    auto v = flying_vehicle();
    std::uint8_t seq = 254;
    const auto bytes = vehicle::mavlink_forward(v, 10.5, seq);
    CHECK(seq == 1);  // three frames, wrapping
    mavlink::Framer framer;
    const auto messages = framer.push(bytes);
    REQUIRE(messages.size() == 3);
    CHECK(framer.stats().dropped_bytes == 0);
    for (const auto& m : messages) {
        CHECK(m.version == 1);
        CHECK(m.sysid == 42);
        CHECK(m.compid == 1);
    }
    CHECK(messages[0].seq == 254);
    CHECK(messages[2].seq == 0);
    CHECK(std::get<mavlink::Attitude>(messages[0].payload) == attitude());
    CHECK(std::get<mavlink::GlobalPositionInt>(messages[1].payload) == position());
    CHECK(std::get<mavlink::SystemTime>(messages[2].payload).time_unix_usec ==
          1'767'225'600'000'000ULL);

    CHECK(vehicle::mavlink_forward(v, 11.5, seq).empty());  // lost: nothing
}

TEST_CASE("GPS time of a UTC time") {
    // The GPS epoch itself, and one leap-second-shifted week later.
    CHECK(vehicle::gps_time_from_unix(315964800.0, 0).week == 0);
    CHECK(vehicle::gps_time_from_unix(315964800.0, 0).itow_ms == 0);
    const auto t = vehicle::gps_time_from_unix(315964800.0 + 604800.0 + 1.5, 18);
    CHECK(t.week == 1);
    CHECK(t.itow_ms == 19500u);
}
