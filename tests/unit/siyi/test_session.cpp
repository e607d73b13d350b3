// A SIYI session against the simulated camera, in process: what gimbald asks on connect
// brings the camera's identity and attitude stream; commands move it; the vehicle feed's
// ticks tell it the aircraft's attitude and aim it at a geopoint.
#include <catch2/catch.hpp>

#include "../vehicle/vehicle_fixtures.hpp"
#include "protocols/siyi/sim/siyi_sim.hpp"
#include "protocols/siyi/siyi_entry.hpp"
#include "protocols/siyi/siyi_protocol.hpp"

using namespace gimbal;
using namespace gimbal::protocols;
using nlohmann::json;

namespace {

struct Loop {
    explicit Loop(SiyiSimOptions sim_options = {}) : sim(sim_options) {
        for (const auto& b : proto.on_connect()) sim.receive(b, t);
    }
    // Runs both sides for `seconds`, feeding what each sends to the other.
    void run(double seconds, const vehicle::VehicleState* vehicle = nullptr) {
        const double end = t + seconds;
        while (t < end - 1e-9) {
            t += 0.05;
            std::vector<std::uint8_t> up;
            sim.advance(t, up);
            std::vector<session::Bytes> replies;
            proto.receive(up, t, events, replies);
            if (vehicle) fed += proto.steer(*vehicle, t, t, replies);
            for (const auto& b : replies) {
                sim.receive(b, t);
                sent.push_back(b);
            }
        }
    }
    void command(std::string_view cmd, const json& request) {
        command::Plan plan;
        const auto error = proto.plan(cmd, request, {t, 0}, plan);
        REQUIRE_FALSE(error);
        for (const auto& p : plan.packets) sim.receive(p.frame, t);
    }

    SiyiOptions options() {
        SiyiOptions o;
        o.geoid_undulation_m = 0;
        return o;
    }
    double t = 1.0;
    SiyiProtocol proto{options()};
    SiyiSim sim;
    std::vector<session::Bytes> sent;
    std::vector<state::Event> events;
    std::size_t fed = 0;
};

// The messages of type M among frames gimbald sent.
template <class M>
std::size_t count_sent(const std::vector<session::Bytes>& sent) {
    std::size_t n = 0;
    siyi::Framer framer;
    for (const auto& b : sent)
        framer.push(b, [&](const siyi::Frame& f) {
            const auto d = siyi::decode_to_gimbal(f);
            if (d && std::holds_alternative<M>(d.value)) ++n;
        });
    return n;
}

}  // namespace

TEST_CASE("session: connect, identity and the attitude stream", "[siyi][session]") {
    SiyiSimOptions o;
    o.model = siyi::Model::zr10;
    Loop loop(o);
    loop.run(1.0);
    const SiyiData& d = loop.proto.state().data();
    CHECK(d.model == siyi::Model::zr10);
    CHECK(d.hardware_id == loop.sim.hardware_id());
    REQUIRE(d.firmware);
    CHECK(d.zoom_max);
    CHECK(loop.proto.telemetry_count() > 10);  // the 20 Hz stream
    CHECK_FALSE(loop.proto.stale(loop.t));
    const json j = loop.proto.snapshot(loop.t);
    CHECK(j["siyi"]["model"] == "ZR10");
    CHECK(j["telemetry"]["hfov"].is_number());
    CHECK(loop.proto.counters().rx_packets > 10);
    CHECK(loop.proto.counters().bad_checksums == 0);
}

TEST_CASE("session: position, rate and zoom move the simulated camera", "[siyi][session]") {
    Loop loop;
    loop.run(0.5);
    loop.command("position", {{"pan", 30}, {"tilt", -45}});
    loop.run(3.0);
    CHECK(loop.sim.yaw_deg() == Approx(-30).margin(0.2));  // SIYI's yaw: left positive
    CHECK(loop.sim.pitch_deg() == Approx(-45).margin(0.2));
    REQUIRE(loop.proto.telemetry());
    CHECK(*loop.proto.telemetry()->pan == Approx(30).margin(0.2));
    CHECK(*loop.proto.telemetry()->tilt == Approx(-45).margin(0.2));

    loop.command("camera_zoom", {{"zoom", 3}});
    loop.run(5.0);
    CHECK(loop.sim.zoom() == Approx(3));
    CHECK(loop.proto.state().data().zoom == Approx(3));

    loop.command("rate", {{"pan", 10}, {"tilt", 0}, {"impulse_time_s", 0.5}});
    const double before = loop.sim.yaw_deg();
    loop.run(2.0);
    const double turned = before - loop.sim.yaw_deg();  // right: SIYI yaw decreases
    CHECK(turned > 2);
    CHECK(turned < 10);  // stopped after the impulse (on the camera's next frame)
}

TEST_CASE("session: center brings the simulated camera home and ends a held heading",
          "[siyi][session]") {
    Loop loop;
    loop.run(0.5);
    loop.command("position", {{"pan", -60}, {"tilt", -30}});
    loop.run(3.0);
    REQUIRE(loop.sim.yaw_deg() == Approx(60).margin(0.5));
    loop.command("center", json::object());
    loop.run(4.0);
    CHECK(loop.sim.yaw_deg() == Approx(0).margin(0.5));
    CHECK(loop.sim.pitch_deg() == Approx(0).margin(0.5));
    REQUIRE(loop.proto.telemetry());
    CHECK(*loop.proto.telemetry()->pan == Approx(0).margin(0.5));
}

TEST_CASE("session: the vehicle feed and a geopoint", "[siyi][session]") {
    // The ZT30's laser hits flat ground 500 m below, where the target is: STATE's target is
    // the laser's point (0x17).
    SiyiSimOptions o;
    o.height_above_ground_m = 500;
    Loop loop(o);
    vehicle::VehicleState vehicle(vehicle_fixtures::options(std::nullopt, 1e9));
    vehicle_fixtures::fix_at(vehicle, loop.t, 45.7, -121.5, 500);
    loop.run(0.5, &vehicle);
    CHECK(loop.fed >= 10);
    CHECK(count_sent<siyi::AircraftAttitude>(loop.sent) ==
          loop.fed - count_sent<siyi::RawGps>(loop.sent));
    loop.command("geopoint", {{"lat", 45.7}, {"lon", -121.49}, {"alt", 0}});
    loop.run(4.0, &vehicle);
    CHECK(loop.sim.yaw_deg() == Approx(-90).margin(1));
    CHECK(loop.sim.pitch_deg() < -30);
    const auto* t = loop.proto.telemetry();
    REQUIRE(t);
    REQUIRE(t->target);
    CHECK(t->target->lat == Approx(45.7).margin(2e-4));
    CHECK(t->target->lon == Approx(-121.49).margin(2e-4));
    REQUIRE(loop.proto.state().data().laser_target);
    CHECK(loop.proto.state().data().laser_range_m);
    CHECK(loop.events.empty());  // no stare asked for

    // stare: one stare_start once the camera is on the point, and STATE `stare`.
    loop.command("position", {{"pan", 0}, {"tilt", 0}});
    loop.run(3.0, &vehicle);
    loop.command("geopoint", {{"lat", 45.7}, {"lon", -121.49}, {"alt", 0}, {"stare", true}});
    loop.run(4.0, &vehicle);
    REQUIRE(loop.events.size() == 1);
    CHECK(loop.events[0].kind == "stare_start");
    CHECK(loop.events[0].fields["lon"] == Approx(-121.49));
    CHECK(loop.events[0].fields["gimbal_data_valid"] == true);
    CHECK(loop.events[0].fields["slant_range"].get<double>() > 900);
    CHECK(loop.proto.snapshot(loop.t)["stare"]["system_time_ms"] ==
          loop.events[0].fields["system_time_ms"]);
}

TEST_CASE("session: a camera that comes up after gimbald is asked by poll, with no vehicle feed",
          "[siyi][session]") {
    SiyiOptions options;
    options.geoid_undulation_m = 0;
    SiyiProtocol proto{options};
    (void)proto.on_connect();  // lost: the camera is not up yet, and says nothing unasked
    SiyiSim sim{SiyiSimOptions{}};
    std::vector<state::Event> events;
    double t = 1.0;
    const auto run = [&](double seconds, bool polled) {
        for (const double end = t + seconds; t < end - 1e-9;) {
            t += 0.1;  // the session's ticks
            std::vector<session::Bytes> out;
            if (polled) proto.poll(t, out);
            for (const auto& b : out) sim.receive(b, t);
            std::vector<std::uint8_t> up;
            sim.advance(t, up);
            std::vector<session::Bytes> replies;
            proto.receive(up, t, events, replies);
            for (const auto& b : replies) sim.receive(b, t);
        }
    };
    run(1.0, false);
    CHECK(proto.stale(t));  // nobody asked it
    run(3.0, true);
    CHECK_FALSE(proto.stale(t));
    REQUIRE(proto.telemetry());
    CHECK(proto.state().data().hardware_id);
}

TEST_CASE("session: a camera that restarts behind the link is asked for its stream again",
          "[siyi][session]") {
    SiyiOptions o;
    o.geoid_undulation_m = 0;
    SiyiProtocol proto(o);
    vehicle::VehicleState vehicle(vehicle_fixtures::options(std::nullopt, 1e9));
    vehicle_fixtures::fix_at(vehicle, 1.0);
    double t = 1.0;
    const auto run = [&](SiyiSim& camera, double seconds) {
        for (const double end = t + seconds; t < end - 1e-9;) {
            t += 0.05;
            std::vector<std::uint8_t> up;
            camera.advance(t, up);
            std::vector<state::Event> events;
            std::vector<session::Bytes> out;
            proto.receive(up, t, events, out);
            proto.steer(vehicle, t, t, out);
            for (const auto& b : out) camera.receive(b, t);
        }
    };
    SiyiSim first{SiyiSimOptions{}};
    for (const auto& b : proto.on_connect()) first.receive(b, t);
    run(first, 1.0);
    const auto before = proto.telemetry_count();
    CHECK(before > 10);
    // A new camera on the same link: no connect, no stream until gimbald asks again.
    SiyiSim second{SiyiSimOptions{}};
    run(second, 2.0);
    CHECK(proto.telemetry_count() > before + 10);
    CHECK_FALSE(proto.stale(t));
}

TEST_CASE("entry: the registry's view of SIYI", "[siyi][session]") {
    const Entry& e = siyi_entry();
    CHECK(e.name == "siyi");
    std::vector<std::string_view> planned;
    for (const auto& c : e.commands) planned.push_back(c.name);
    CHECK(planned == std::vector<std::string_view>{"position", "center", "rate", "camera_zoom",
                                                   "geopoint", "path"});
    const json gimbal = {{"name", "g"}, {"protocol", "siyi"}};
    auto session = e.make_session(SessionSettings{}, gimbal);
    CHECK(session->name() == "siyi");
    CHECK(session->supports("camera_zoom"));
    auto device = e.simulator.make(SimScenario{});
    REQUIRE(device);
    CHECK(e.make_splitter());
    CHECK(e.make_track_decoder());
}
