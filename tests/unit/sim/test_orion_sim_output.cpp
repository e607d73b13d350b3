// The simulated Orion's own output: rates, telemetry content, answers to requests.
#include <catch2/catch.hpp>
#include <map>

#include "protocols/orion/codec/packets.hpp"
#include "sim/frames.hpp"
#include "sim/terrain.hpp"
#include "sim_harness.hpp"

using namespace gimbal;
using namespace sim_test;
namespace pkt = orion::pkt;

TEST_CASE("periodic packets come at the ICD's rates", "[sim][orion][rates]") {
    Harness h;
    auto frames = h.run(0);                 // t = 0
    const auto rest = h.run(9.999, 0.013);  // up to just before t = 10
    frames.insert(frames.end(), rest.begin(), rest.end());

    std::map<std::uint8_t, std::size_t> counts;
    for (const auto& f : frames) ++counts[f.id];
    CHECK(counts[pkt::geolocate_telemetry] == 100);  // 10 Hz
    CHECK(counts[pkt::performance] == 40);           // 4 Hz
    CHECK(counts[pkt::ins_quality] == 10);           // 1 Hz
    CHECK(counts[pkt::gps_data] == 10);              // 1 Hz
    CHECK(counts[pkt::diagnostics] == 4);            // every 3 s: 0, 3, 6, 9
    CHECK(counts[pkt::software_diagnostics] == 10);  // 1 Hz
    CHECK(counts[pkt::vibration] == 2);              // every 5 s
    CHECK(counts[pkt::laser_states] == 10);
    CHECK(counts[pkt::retract_status] == 10);
    CHECK(counts[pkt::reset_source] == 1);  // once, at boot
    CHECK(h.framer_stats().bad_checksums == 0);
    CHECK(h.framer_stats().dropped_bytes == 0);

    // Every packet decodes with its own declaration.
    for (const auto& f : frames) {
        bool ok = false;
        orion::dispatch(f.id,
                        [&]<class P>() { ok = static_cast<bool>(orion::decode<P>(f.data())); });
        INFO("packet id " << int(f.id));
        CHECK(ok);
    }
}

TEST_CASE("telemetry timestamps follow the model clock", "[sim][orion][telemetry]") {
    sim::OrionSimOptions o;
    o.uptime_at_start_ms = 60000;
    o.gps_time_at_start_s = 1419724818.0 + 0.5;
    Harness h(o);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(2.05));
    REQUIRE(t.size() == 21);
    CHECK(t[0].system_time_ms == 60000);
    CHECK(t[20].system_time_ms == 62000);
    CHECK(t[20].system_time_ms - t[19].system_time_ms == 100);
    // 1419724818 s after the GPS epoch is week 2347, 259218 s into it.
    CHECK(t[0].gps_week == 2347);
    CHECK(t[0].gps_itow_ms == 259218500);
    CHECK(t[20].gps_itow_ms == 259220500);
    CHECK(t[0].leap_seconds == 18);
}

TEST_CASE("a start time before the GPS epoch reports week 0, not a wrapped week",
          "[sim][orion][telemetry]") {
    sim::OrionSimOptions o;
    o.gps_time_at_start_s = sim::gps_time_from_unix_s(0);  // 1970: ten years before GPS began
    Harness h(o);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(0.05));
    REQUIRE_FALSE(t.empty());
    CHECK(t[0].gps_week == 0);
    CHECK(t[0].gps_itow_ms == 0);
    const auto g = decoded<orion::GpsData>(h.run(1.05));
    REQUIRE_FALSE(g.empty());
    CHECK(g.back().week == 0);
}

TEST_CASE("telemetry places the gimbal on its circle and the line of sight on the terrain",
          "[sim][orion][telemetry]") {
    sim::OrionSimOptions o;
    o.terrain_alt_m = 250;
    Harness h(o);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(30));
    REQUIRE(t.size() > 250);
    const sim::Vec3 centre = sim::to_ecef({o.lat_deg * sim::deg, o.lon_deg * sim::deg, o.alt_m});
    for (const auto& s : t) {
        const sim::Vec3 gimbal = sim::to_ecef({s.lat, s.lon, s.alt});
        CHECK(norm(gimbal - centre) == Approx(o.radius_m).margin(1.0));
        CHECK(s.alt == Approx(o.alt_m).margin(0.001));
        CHECK(std::hypot(s.vel_ned[0], s.vel_ned[1]) == Approx(o.speed_mps).margin(0.01));
        CHECK(s.mode == orion::Mode::position);
        CHECK(s.range_source == orion::RangeSource::internal);
        CHECK(s.geoid_undulation == Approx(o.geoid_undulation_m).margin(0.01));
        // Looking 30 degrees down from 1250 m above the terrain: about 2500 m of range.
        const sim::Vec3 los{s.los_ecef[0], s.los_ecef[1], s.los_ecef[2]};
        CHECK(norm(los) == Approx(2500).epsilon(0.03));
        CHECK(sim::to_lla(gimbal + los).alt == Approx(250).margin(2.0));
        CHECK(s.pixel_width == 1920);
        CHECK(s.hfov > 0.5);
    }
}

TEST_CASE("by default the line of sight meets the simulator's terrain", "[sim][orion][telemetry]") {
    Harness h;  // no terrain_alt_m: the analytic terrain of sim/terrain.hpp
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(20));
    REQUIRE(t.size() > 150);
    double lowest = 1e9, highest = -1e9;
    for (const auto& s : t) {
        REQUIRE(s.range_source == orion::RangeSource::internal);
        const sim::Vec3 los{s.los_ecef[0], s.los_ecef[1], s.los_ecef[2]};
        const sim::Lla target = sim::to_lla(sim::to_ecef({s.lat, s.lon, s.alt}) + los);
        const double ground = sim::terrain_height(target.lat / sim::deg, target.lon / sim::deg);
        // losECEF is whole metres: the reported point is within a metre or so of the ground.
        CHECK(target.alt == Approx(ground).margin(3.0));
        lowest = std::min(lowest, target.alt);
        highest = std::max(highest, target.alt);
    }
    // Not a flat world: the ground seen along the circle rises and falls.
    CHECK(highest - lowest > 50);
}

TEST_CASE("a line of sight above the horizon has no location", "[sim][orion][telemetry]") {
    Harness h;
    h.run(0);
    orion::Cmd up;
    up.cmd.mode = orion::Mode::position;
    up.cmd.target = {0, 0.3};
    h.send_packet(up);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(3));
    REQUIRE(!t.empty());
    CHECK(t.back().tilt == Approx(0.3).margin(0.001));
    CHECK(t.back().los_ecef == std::array<double, 3>{0, 0, 0});
    CHECK(t.back().range_source == orion::RangeSource::none);
}

TEST_CASE("zero-length requests are answered with that packet", "[sim][orion][requests]") {
    Harness h;
    h.run(0.05);
    const std::uint8_t ids[] = {pkt::cameras,          pkt::limits,
                                pkt::network_settings, pkt::network_video,
                                pkt::ins_options,      pkt::uart_config,
                                pkt::startup_cmd,      pkt::laser_states,
                                pkt::retract_status,   pkt::network_diagnostics,
                                pkt::reset_source,     pkt::cmd,
                                pkt::diagnostics,      pkt::gps_data,
                                pkt::ins_quality};
    for (const auto id : ids) {
        h.run(0.01);  // keep the periodic packets out of the answer's window
        h.request(id);
        const auto got = h.run(0.001, 0.001);
        INFO("request for id " << int(id));
        CHECK(count_id(got, id) == 1);
    }

    h.request(pkt::cameras);
    const auto cameras = decoded<orion::Cameras>(h.run(0.001, 0.001));
    REQUIRE(cameras.size() == 1);
    REQUIRE(cameras[0].cameras.size() == 2);
    CHECK(cameras[0].cameras[0].type == orion::CameraType::visible);
    CHECK(cameras[0].cameras[1].type == orion::CameraType::lwir);

    h.request(pkt::limits);
    const auto limits = decoded<orion::Limits>(h.run(0.001, 0.001));
    REQUIRE(limits.size() == 1);
    CHECK(limits[0].max_vel[0] == Approx(60 * sim::deg).margin(0.001));
    CHECK(limits[0].min_pos[1] == Approx(-120 * sim::deg).margin(0.001));

    h.request(pkt::network_settings);
    const auto net = decoded<orion::NetworkSettings>(h.run(0.001, 0.001));
    REQUIRE(net.size() == 1);
    CHECK(net[0].ip == 0xC0A80114);
}

TEST_CASE("a version request is answered with every version packet", "[sim][orion][requests]") {
    Harness h;
    h.run(0.05);
    h.request(pkt::crown_version);
    const auto got = h.run(0.001, 0.001);
    for (const auto id : {pkt::clevis_version, pkt::crown_version, pkt::payload_version,
                          pkt::tracker_version, pkt::retract_version, pkt::lensctl_version})
        CHECK(count_id(got, id) == 1);
    const auto crown = decoded<orion::CrownVersion>(got);
    REQUIRE(crown.size() == 1);
    CHECK(crown[0].version == "1.4.7-sim");
    CHECK(sim::orion_sim_crown_version_frame() == orion::to_wire(crown[0]));

    h.request(pkt::board);
    CHECK(count_id(h.run(0.001, 0.001), pkt::board) == 3);
}

TEST_CASE("requests for packets the gimbal does not have get no answer", "[sim][orion][requests]") {
    Harness h;
    h.run(0.05);
    for (const std::uint8_t id :
         {pkt::geopoint_cmd, pkt::path, pkt::user_data, std::uint8_t{250}}) {
        h.request(id);
        CHECK(h.run(0.001, 0.001).empty());
    }
}

TEST_CASE("settings written are kept and confirmed", "[sim][orion][requests]") {
    Harness h;
    h.run(0.05);
    orion::NetworkSettings n;
    n.ip = 0x0A000002;
    n.mask = 0xFF000000;
    n.gateway = 0x0A000001;
    h.send_packet(n);
    auto got = decoded<orion::NetworkSettings>(h.run(0.001, 0.001));
    REQUIRE(got.size() == 1);
    CHECK(got[0].ip == 0x0A000002);
    h.request(pkt::network_settings);
    got = decoded<orion::NetworkSettings>(h.run(0.001, 0.001));
    REQUIRE(got.size() == 1);
    CHECK(got[0].gateway == 0x0A000001);

    orion::UartConfig u;
    u.port = orion::UserDataPort::fp1;
    u.baud = 57600;
    u.protocol = orion::UartProtocol::nmea_gps;
    h.send_packet(u);
    h.run(0.001, 0.001);
    h.send(orion::frame_bytes(pkt::uart_config, Bytes{4}));  // one-byte form: port FP1
    auto uart = decoded<orion::UartConfig>(h.run(0.001, 0.001));
    REQUIRE(uart.size() == 1);
    CHECK(uart[0].baud == 57600);
    CHECK(uart[0].protocol == orion::UartProtocol::nmea_gps);
}

TEST_CASE("new limits change how fast the axes slew", "[sim][orion][requests]") {
    Harness h;
    h.run(0);
    h.request(pkt::limits);
    auto limits = decoded<orion::Limits>(h.run(0.001, 0.001));
    REQUIRE(limits.size() == 1);
    limits[0].max_vel = {0.1, 0.1};  // rad/s
    h.send_packet(limits[0]);
    orion::Cmd c;
    c.cmd.mode = orion::Mode::position;
    c.cmd.target = {1.0, -0.5236};
    h.send_packet(c);
    const auto t = decoded<orion::GeolocateTelemetry>(h.run(2.0));
    REQUIRE(!t.empty());
    CHECK(t.back().pan == Approx(0.2).margin(0.005));
}
