// The protocol registry: every entry complete and consistent with the command catalogue, and
// each entry's parts working together end to end: its session configures its simulator, the
// simulator's bytes come back as telemetry, the recorder's splitter and the export's track
// decoder see the same frames.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "../vehicle/vehicle_fixtures.hpp"
#include "command/catalogue.hpp"
#include "protocols/registry.hpp"
#include "state/messages.hpp"

using namespace gimbal;
using nlohmann::json;
using protocols::Entry;

namespace {

// A gimbal configuration object as config.cpp writes it, for protocol `name`.
json gimbal_config(const Entry& e) {
    return {{"name", "g"}, {"protocol", e.name}, {"link", {{"type", "sim"}}}};
}

struct Run {
    std::vector<std::uint8_t> stream;  // everything the simulated gimbal sent
    std::uint64_t telemetry = 0;
    session::FrameCounters counters;
    json state;
    std::unique_ptr<session::Protocol> session;  // its state, as the capabilities read it
};

// An aircraft level over the Columbia river gorge, heading east, as its autopilot reports it.
void report_vehicle(vehicle::VehicleState& v, double now_s) {
    using vehicle_fixtures::from;
    mavlink::Heartbeat hb;
    hb.system_status = static_cast<std::uint8_t>(mavlink::MavState::active);
    v.apply(from(1, hb), now_s);
    mavlink::Attitude a;
    a.yaw = 1.5f;
    v.apply(from(1, a), now_s);
    mavlink::GlobalPositionInt p;
    p.lat = 457000000;
    p.lon = -1215000000;
    p.alt = 500000;
    v.apply(from(1, p), now_s);
}

// The session asks the simulated gimbal for what it needs (on_connect), then listens for
// `seconds`, steered at the vehicle feed's ticks (a protocol that aims from the vehicle's
// state sends then).
Run run(const Entry& e, double seconds) {
    auto session = e.make_session(protocols::SessionSettings{}, gimbal_config(e));
    protocols::SimScenario scenario;
    scenario.unix_time_s = 1'790'000'000.0;
    auto device = e.simulator.make(scenario);
    for (const auto& bytes : session->on_connect()) device->receive(bytes, 0.0);
    Run r;
    std::vector<state::Event> events;
    std::vector<session::Bytes> replies;
    vehicle::VehicleState vehicle(vehicle_fixtures::options());
    for (double t = 0.01; t <= seconds; t += 0.01) {
        if (std::fmod(t, protocols::feed_tick_s) < 0.01) {
            report_vehicle(vehicle, t);
            std::vector<session::Bytes> steering;
            session->steer(vehicle, t, t, steering);
            for (const auto& bytes : steering) device->receive(bytes, t);
        }
        std::vector<std::uint8_t> out;
        device->advance(t, out);
        session->receive(out, t, events, replies);
        r.stream.insert(r.stream.end(), out.begin(), out.end());
    }
    r.telemetry = session->telemetry_count();
    r.counters = session->counters();
    r.state = session->snapshot(seconds);
    r.state["protocol"] = std::string(session->name());
    r.session = std::move(session);
    return r;
}

}  // namespace

TEST_CASE("every protocol has one complete entry", "[registry]") {
    std::set<std::string_view> names, dissectors;
    std::set<protocols::ProtocolId> ids;
    for (const auto id : protocols::all_protocol_ids) {
        const Entry& e = protocols::entry(id);
        INFO(e.name);
        CHECK(e.id == id);
        CHECK(names.insert(e.name).second);
        CHECK(dissectors.insert(e.dissector).second);
        CHECK(ids.insert(e.id).second);
        CHECK_FALSE(e.display_name.empty());
        CHECK(protocols::to_string(id) == e.name);
        CHECK(protocols::parse_protocol(e.name) == id);
        CHECK(protocols::find(e.name) == &e);
        CHECK(protocols::find_by_dissector(e.dissector) == &e);
        CHECK(e.features.point_angles);  // every gimbal points at angles
        CHECK(e.make_session != nullptr);
        CHECK(e.make_feeder != nullptr);
        CHECK(e.make_splitter != nullptr);
        CHECK(e.make_track_decoder != nullptr);
        CHECK(e.simulator.make != nullptr);
        CHECK(e.simulator.defaults != nullptr);
        CHECK(e.simulator.fault_frames != nullptr);
        CHECK(e.simulator.make_rx_decoder != nullptr);
        CHECK_FALSE(e.simulator.manual.empty());
        CHECK_FALSE(e.simulator.rx_log_manual.empty());
        CHECK((e.simulator.is_discovery_request == nullptr) ==
              (e.simulator.discovery_reply == nullptr));
    }
    CHECK(protocols::names().size() == protocols::all_protocol_ids.size());
    CHECK_FALSE(protocols::parse_protocol("gopro"));
    CHECK(protocols::find("gopro") == nullptr);
    CHECK(protocols::find_by_dissector("data") == nullptr);
    CHECK(protocols::is_state_key("capabilities"));  // the key the daemon adds from the entry
}

TEST_CASE("STATE keys: the shared ones and each protocol's own, declared by its entry",
          "[registry]") {
    for (const auto* e : protocols::entries()) {
        INFO(e->name);
        for (const auto key : e->state_keys) {
            INFO(key);
            CHECK_FALSE(state::is_shared_state_key(key));  // a protocol's own, not a shared one
            CHECK(protocols::is_state_key(key));
            auto read = state::read_state_keys(json{key}, protocols::is_state_key);
            CHECK(read);
        }
    }
    CHECK(protocols::is_state_key("telemetry"));
    CHECK_FALSE(protocols::is_state_key("telemtry"));
    // Without the registry only the shared keys are known (lib/state sits beneath it).
    CHECK_FALSE(state::read_state_keys(json{"ins"}));
    CHECK(state::read_state_keys(json{"ins"}, protocols::is_state_key));
}

TEST_CASE("a protocol plans exactly the catalogue commands its entry lists", "[registry]") {
    for (const auto* e : protocols::entries()) {
        auto session = e->make_session(protocols::SessionSettings{}, gimbal_config(*e));
        CHECK(session->name() == e->name);
        CHECK(session->capabilities().names() == session::feature_names(e->features));
        for (const auto& planned : e->commands) {
            INFO(e->name << " lists " << planned.name);
            const auto* spec = command::find_command(planned.name);
            REQUIRE(spec != nullptr);
            CHECK(spec->scope == command::Scope::protocol);
            CHECK_FALSE(planned.wire.empty());
        }
        for (const auto& c : command::catalogue()) {
            INFO(e->name << ": " << c.name);
            CHECK(session->supports(c.name) == e->plans(c.name));
        }
    }
    // Every protocol command has a protocol that plans it.
    for (const auto& c : command::catalogue()) {
        INFO(c.name);
        if (c.scope == command::Scope::protocol)
            CHECK_FALSE(protocols::planners_of(c.name).empty());
        else
            CHECK(protocols::planners_of(c.name).empty());
    }
}

TEST_CASE("each entry's session, simulator, splitter and track decoder work together",
          "[registry]") {
    for (const auto* e : protocols::entries()) {
        INFO(e->name);
        const Run r = run(*e, 3.0);
        CHECK(r.telemetry > 10);
        CHECK(r.counters.bad_checksums == 0);
        CHECK(r.counters.dropped_bytes == 0);
        CHECK(r.state["protocol"] == e->name);
        // Every key the session writes is one a subscriber may name, and every key the
        // entry declares is written: the declaration is the session's.
        for (const auto& [key, value] : r.state.items()) {
            INFO(key);
            CHECK(protocols::is_state_key(key));
        }
        for (const auto key : e->state_keys) {
            INFO(key);
            CHECK(r.state.contains(std::string(key)));
        }

        // The recorder's splitter: the pieces are the stream, and the frames the session's.
        auto splitter = e->make_splitter();
        std::vector<std::uint8_t> joined;
        std::uint64_t frames = 0;
        const framing::StreamSplitter::Piece piece = [&](std::span<const std::uint8_t> b,
                                                         bool is_frame) {
            joined.insert(joined.end(), b.begin(), b.end());
            if (is_frame) ++frames;
        };
        for (std::size_t at = 0; at < r.stream.size(); at += 97)
            splitter->push(
                std::span(r.stream).subspan(at, std::min<std::size_t>(97, r.stream.size() - at)),
                piece);
        splitter->flush(piece);
        CHECK(joined == r.stream);
        CHECK(frames == r.counters.rx_packets);

        // The export hook: one track point per telemetry frame, each with the aircraft when
        // the gimbal's link carries its position (a MAVLink device's and a SIYI camera's do
        // not).
        auto decoder = e->make_track_decoder();
        std::vector<protocols::TrackPoint> points;
        decoder->push(r.stream, 1'790'000'000'000'000, points);
        CHECK(decoder->frames() == r.counters.rx_packets);
        CHECK(decoder->decode_errors() == 0);
        CHECK(points.size() == r.telemetry);
        REQUIRE_FALSE(points.empty());
        CHECK(points.back().aircraft.has_value() ==
              (e->id != protocols::ProtocolId::mavlink && e->id != protocols::ProtocolId::siyi));

        // The capabilities read that state.
        const auto& caps = r.session->capabilities();
        CHECK(caps.line_of_sight().has_value());
        const auto view = caps.view();
        CHECK(view.lat_deg.has_value());
        CHECK(view.lon_deg.has_value());
        CHECK_FALSE(caps.identity().vendor.empty());
    }
}

TEST_CASE("the rx-log decoder reads what the session sends", "[registry]") {
    for (const auto* e : protocols::entries()) {
        INFO(e->name);
        auto session = e->make_session(protocols::SessionSettings{}, gimbal_config(*e));
        auto decoder = e->simulator.make_rx_decoder();
        std::vector<json> lines;
        std::size_t sent = 0;
        for (const auto& bytes : session->on_connect()) {
            decoder->push(bytes, lines);
            ++sent;
        }
        CHECK(lines.size() == sent);
        for (const auto& line : lines) {
            CHECK(line.contains("hex"));
            CHECK(line.contains("len"));
        }
    }
}

TEST_CASE("sim flags: every key has a default, and given options reach the model", "[registry]") {
    for (const auto* e : protocols::entries()) {
        INFO(e->name);
        const json defaults = e->simulator.defaults();
        for (const auto& f : e->simulator.flags) {
            INFO(f.name);
            CHECK(f.name.starts_with("--"));
            CHECK(defaults.contains(std::string(f.key)));
        }
    }
}

TEST_CASE("discovery: only the protocol that has it answers", "[registry]") {
    for (const auto* e : protocols::entries()) {
        if (!e->simulator.is_discovery_request) continue;
        const auto reply = e->simulator.discovery_reply();
        CHECK_FALSE(reply.empty());
        CHECK_FALSE(e->simulator.is_discovery_request(reply));  // a reply is not a request
        CHECK_FALSE(e->simulator.is_discovery_request(std::vector<std::uint8_t>{1, 2, 3}));
    }
}

TEST_CASE("discovery: gimbald's request is what the simulated gimbal answers", "[registry]") {
    int with_discovery = 0;
    for (const auto* e : protocols::entries()) {
        INFO(e->name);
        // gimbald finds a protocol's gimbals exactly when its simulator can be found.
        CHECK(static_cast<bool>(e->discovery) == (e->simulator.is_discovery_request != nullptr));
        CHECK((e->discovery.request == nullptr) == (e->discovery.is_reply == nullptr));
        if (!e->discovery) continue;
        ++with_discovery;
        CHECK(e->simulator.is_discovery_request(e->discovery.request()));
        CHECK(e->discovery.is_reply(e->simulator.discovery_reply()));
        CHECK_FALSE(e->discovery.is_reply(std::vector<std::uint8_t>{'h', 'i'}));
    }
    CHECK(with_discovery == 1);  // the Orion's
}

TEST_CASE("feeders: kinds from the gimbal's feed configuration", "[registry]") {
    for (const auto* e : protocols::entries()) {
        auto feeder = e->make_feeder(gimbal_config(*e));
        CHECK_FALSE(feeder->kind().empty());
    }
}
