// The Orion state model: packets in, STATE (contract section 5) and events out.
#include <catch2/catch.hpp>

#include <cmath>

#include "geo/sampled_surface.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/orion_state.hpp"

using namespace gimbal;
using nlohmann::json;

namespace {

template <class P>
orion::Frame frame_of(const P& packet) {
    orion::Frame f;
    f.id = P::id;
    orion::encode(packet, f.payload);
    return f;
}

orion::GeolocateTelemetry telemetry(orion::Mode mode) {
    orion::GeolocateTelemetry t;
    t.system_time_ms = 1000;
    t.gps_week = 2443;  // 2026-11-01 .. 2026-11-07
    t.gps_itow_ms = 6 * 86400000u + 6 * 3600000u + 41 * 60000u + 50123u;
    t.leap_seconds = 18;
    t.geoid_undulation = -21.5;
    t.lat = 45.7 * orion::pi / 180.0;
    t.lon = -121.5 * orion::pi / 180.0;
    t.alt = 1500;
    t.quat = {1, 0, 0, 0};
    t.pan = 0.5;
    t.tilt = -0.3;
    t.mode = mode;
    t.los_ecef = {100, -200, -1000};
    return t;
}

}  // namespace

TEST_CASE("GPS week and time of week minus leap seconds give UTC", "[state]") {
    // GPS week 0 starts 1980-01-06; leap seconds are subtracted.
    CHECK(state::gps_to_utc_iso(0, 0, 0) == "1980-01-06T00:00:00.000Z");
    CHECK(state::gps_to_utc_iso(0, 18000, 18) == "1980-01-06T00:00:00.000Z");
    // Week 2443 starts Sunday 2026-11-01.
    CHECK(state::gps_to_utc_iso(2443, 6 * 86400000u + 6 * 3600000u + 41 * 60000u + 50123u + 18000u,
                                18) == "2026-11-07T06:41:50.123Z");
}

TEST_CASE("telemetry reaches STATE with derived fields", "[state]") {
    state::OrionState s(1.0);
    std::vector<state::Event> events;
    CHECK(s.stale(0.0));
    CHECK(s.snapshot(0.0)["telemetry"].is_null());
    REQUIRE(s.apply(frame_of(telemetry(orion::Mode::geopoint)), 10.0, events));
    CHECK(events.empty());
    const json snap = s.snapshot(10.25);
    const json& t = snap["telemetry"];
    CHECK(t["lat"].get<double>() == Approx(45.7).margin(1e-6));
    CHECK(t["lon"].get<double>() == Approx(-121.5).margin(1e-6));
    CHECK(t["alt_msl"].get<double>() == Approx(1521.5));
    CHECK(t["mode"] == "geopoint");
    CHECK(t["pan"].get<double>() == Approx(0.5 * 180 / orion::pi).margin(0.01));
    CHECK(t["roll"].get<double>() == Approx(0).margin(1e-6));
    CHECK(t["age_s"].get<double>() == Approx(0.25));
    CHECK(t["utc"] == "2026-11-07T06:41:32.123Z");
    REQUIRE(t["target"].is_object());
    CHECK(t["target"]["alt"].get<double>() < 1500.0);
    CHECK_FALSE(s.stale(10.9));
    for (const char* key : {"ins", "gps", "lasers", "versions", "cameras", "limits", "stare"})
        CHECK(snap.contains(key));
}

TEST_CASE("mode changes, staleness and stare starts become events", "[state]") {
    state::OrionState s(1.0);
    std::vector<state::Event> events;
    s.apply(frame_of(telemetry(orion::Mode::rate)), 0.0, events);
    s.apply(frame_of(telemetry(orion::Mode::geopoint)), 0.1, events);
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == "mode");
    CHECK(events[0].fields == json{{"from", "rate"}, {"to", "geopoint"}});

    events.clear();
    s.tick(1.0, events);
    CHECK(events.empty());
    s.tick(1.2, events);
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == "lost");
    s.tick(2.0, events);
    CHECK(events.size() == 1);  // once per loss

    events.clear();
    orion::StareStart stare;
    stare.system_time_ms = 777;
    s.apply(frame_of(stare), 2.0, events);
    REQUIRE(events.size() == 1);
    CHECK(events[0].kind == "stare_start");
    CHECK(s.last_stare_time_ms() == 777u);
    CHECK(s.snapshot(2.0)["stare"]["system_time_ms"] == 777);
}

TEST_CASE("a packet too short to decode changes nothing", "[state]") {
    state::OrionState s(1.0);
    std::vector<state::Event> events;
    REQUIRE(s.apply(frame_of(telemetry(orion::Mode::rate)), 0.0, events));
    const json before = s.snapshot(0.5);
    orion::Frame short_frame;
    short_frame.id = orion::pkt::geolocate_telemetry;
    short_frame.payload.size = 10;
    CHECK_FALSE(s.apply(short_frame, 0.4, events));
    CHECK(s.decode_errors() == 1);
    CHECK_THAT(s.last_decode_error(), Catch::Contains("geolocate_telemetry"));
    CHECK(s.snapshot(0.5) == before);
}

TEST_CASE("laser states become the STATE lasers array", "[state]") {
    state::OrionState s(1.0);
    std::vector<state::Event> events;
    CHECK(s.snapshot(0.0)["lasers"].is_null());
    orion::LaserStates lasers;
    lasers.states.resize(2);
    lasers.states[0].type = orion::LaserType::pointer;
    lasers.states[0].enabled = true;
    lasers.states[1].type = orion::LaserType::lightware;
    lasers.states[1].armed = true;
    REQUIRE(s.apply(frame_of(lasers), 3.0, events));
    const json arr = s.snapshot(3.5)["lasers"];
    REQUIRE(arr.is_array());
    REQUIRE(arr.size() == 2);
    CHECK(arr[0]["type"] == "pointer");
    CHECK(arr[0]["enabled"] == true);
    CHECK(arr[1]["armed"] == true);
    CHECK(arr[1]["age_s"].get<double>() == Approx(0.5));
}

TEST_CASE("telemetry's footprint and ground meet the terrain, else the target's altitude",
          "[state][terrain]") {
    orion::GeolocateTelemetry t = telemetry(orion::Mode::position);
    t.pan = 0;
    t.tilt = -60 * orion::pi / 180;
    t.hfov = 30 * orion::pi / 180;
    t.vfov = 20 * orion::pi / 180;
    // Without terrain: the flat world at the target's altitude; the ground is the target.
    json j = state::telemetry_json(t);
    REQUIRE(j["target"].is_object());
    CHECK(j["footprint_surface"] == "ellipsoid");
    REQUIRE(j["footprint"].size() == 4);
    REQUIRE(j["ground"].is_object());
    CHECK(j["ground"]["surface"] == "ellipsoid");
    CHECK(j["ground"]["alt"].get<double>() ==
          Approx(j["target"]["alt"].get<double>()).margin(1e-3));

    // A plateau at 700 m: every key on it (the gimbal's target stays as reported).
    geo::SampledSurface plateau([](double, double) { return 700.0; }, geo::Lattice{}, 700.0,
                                geo::GeoRect{45.5, 45.9, -121.7, -121.3});
    j = state::telemetry_json(t, &plateau);
    CHECK(j["footprint_surface"] == "terrain");
    CHECK(j["ground"]["surface"] == "terrain");
    CHECK(j["ground"]["alt"].get<double>() == Approx(700).margin(1e-3));
    // Looking 60 degrees down from 800 m above it.
    CHECK(j["ground"]["range_m"].get<double>() ==
          Approx(800 / std::sin(orion::pi / 3)).margin(0.5));
    CHECK(j["target"] == state::telemetry_json(t)["target"]);

    // No target and no terrain: nothing; terrain alone still answers.
    t.los_ecef = {0, 0, 0};
    j = state::telemetry_json(t);
    CHECK(j["footprint"].is_null());
    CHECK(j["footprint_surface"].is_null());
    CHECK(j["ground"].is_null());
    j = state::telemetry_json(t, &plateau);
    CHECK(j["ground"]["surface"] == "terrain");

    // Through the state model: STATE carries what it was given at each packet.
    state::OrionState s(1.0, &plateau);
    std::vector<state::Event> events;
    REQUIRE(s.apply(frame_of(t), 1.0, events));
    CHECK(s.snapshot(1.0)["telemetry"]["footprint_surface"] == "terrain");
}
