// The registry's vehicle-feed hooks: which packets each protocol's feeder sends at which
// 50 ms tick (the schedule VehicleFeed used to hold), decoded with the receiving side's codec.
#include <catch2/catch.hpp>

#include "../vehicle/vehicle_fixtures.hpp"
#include "mavlink/framer.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/registry.hpp"
#include "protocols/viewpro/codec/input_framer.hpp"

using namespace gimbal;
using nlohmann::json;
using protocols::FeedBytes;
using vehicle_fixtures::from;

namespace {

vehicle::VehicleState fresh_vehicle() {
    vehicle::VehicleState v(vehicle_fixtures::options());
    mavlink::Heartbeat hb;
    hb.base_mode = mavlink::mav_mode_flag_safety_armed;
    hb.system_status = static_cast<std::uint8_t>(mavlink::MavState::active);
    v.apply(from(42, hb), 10.0);
    mavlink::Attitude a;
    a.yaw = 1.0f;
    v.apply(from(42, a), 10.0);
    mavlink::GlobalPositionInt p;
    p.lat = 457000000;
    p.lon = -1215000000;
    p.alt = 1500000;
    p.relative_alt = 300000;
    v.apply(from(42, p), 10.0);
    return v;
}

std::unique_ptr<protocols::VehicleFeeder> feeder(std::string_view protocol, json feed) {
    const json gimbal = {{"name", "g"}, {"protocol", protocol}, {"feed", std::move(feed)}};
    return protocols::find(protocol)->make_feeder(gimbal);
}

// Packets sent at ticks 0..n-1, by tick.
std::vector<std::vector<FeedBytes>> schedule(protocols::VehicleFeeder& f,
                                             const vehicle::VehicleState& v, std::uint64_t n) {
    std::vector<std::vector<FeedBytes>> out(n);
    for (std::uint64_t tick = 0; tick < n; ++tick)
        f.tick(v, {10.0, 1'767'225'600.0, tick}, out[tick]);
    return out;
}

std::vector<std::uint8_t> orion_ids(const std::vector<FeedBytes>& packets) {
    std::vector<std::uint8_t> ids;
    orion::Framer framer;
    for (const auto& p : packets)
        framer.push(p, [&](const orion::Frame& f) { ids.push_back(f.id); });
    return ids;
}

}  // namespace

TEST_CASE("Orion feeder: AutopilotData at 1 Hz, GPS_DATA at 4 Hz when asked") {
    const auto v = fresh_vehicle();
    auto f = feeder("orion", {{"autopilot", true}, {"gps", true}});
    CHECK(f->kind() == "orion");
    const auto sent = schedule(*f, v, 41);
    for (std::uint64_t tick = 0; tick < sent.size(); ++tick) {
        INFO("tick " << tick);
        std::vector<std::uint8_t> want;
        if (tick % 20 == 0) want.push_back(orion::AutopilotData::id);
        if (tick % 5 == 0) want.push_back(orion::GpsData::id);
        CHECK(orion_ids(sent[tick]) == want);
    }
    auto quiet = feeder("orion", {{"autopilot", false}, {"gps", false}});
    for (const auto& packets : schedule(*quiet, v, 41)) CHECK(packets.empty());
    // The default feed: AutopilotData only.
    const json no_feed = {{"name", "g"}, {"protocol", "orion"}};
    auto by_default = protocols::find("orion")->make_feeder(no_feed);
    CHECK(orion_ids(schedule(*by_default, v, 1)[0]) ==
          std::vector<std::uint8_t>{orion::AutopilotData::id});
}

TEST_CASE("Orion feeder: a feed change goes out at once") {
    const auto v = fresh_vehicle();
    std::vector<FeedBytes> out;
    feeder("orion", {{"autopilot", true}, {"gps", false}})
        ->connection_changed(v, {10.0, 0.0, 7}, out);
    CHECK(orion_ids(out) == std::vector<std::uint8_t>{orion::AutopilotData::id});
    out.clear();
    feeder("orion", {{"autopilot", false}, {"gps", true}})
        ->connection_changed(v, {10.0, 0.0, 7}, out);
    CHECK(out.empty());
}

TEST_CASE("Viewpro feeder: IN2, IN1 or MAVLink at 10 Hz") {
    const auto v = fresh_vehicle();
    for (const std::string kind : {"in2", "in1"}) {
        INFO(kind);
        auto f = feeder("viewpro", kind);
        CHECK(f->kind() == kind);
        const auto sent = schedule(*f, v, 6);
        for (std::uint64_t tick = 0; tick < sent.size(); ++tick) {
            REQUIRE(sent[tick].size() == (tick % 2 == 0 ? 1u : 0u));
            if (sent[tick].empty()) continue;
            viewpro::InputFramer framer;
            const auto frames = framer.push(sent[tick][0]);
            REQUIRE(frames.size() == 1);
            CHECK(viewpro::to_string(frames[0].kind) == kind);
        }
    }
    auto f = feeder("viewpro", "mavlink");
    CHECK(f->kind() == "mavlink");
    const auto sent = schedule(*f, v, 3);
    REQUIRE(sent[0].size() == 1);
    CHECK(sent[1].empty());
    mavlink::Framer framer;
    std::size_t messages = 0;
    framer.push(sent[0][0], [&](const mavlink::Message&) { ++messages; });
    CHECK(messages == 2);  // ATTITUDE and GLOBAL_POSITION_INT (no SYSTEM_TIME received)
    std::vector<FeedBytes> out;
    f->connection_changed(v, {10.0, 0.0, 0}, out);
    CHECK(out.empty());
}
