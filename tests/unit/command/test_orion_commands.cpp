// Orion commands of contract section 4.2: parameters -> exact wire packets, and every
// refusal sends nothing.
#include <catch2/catch.hpp>
#include <cmath>

#include "command/envelope.hpp"
#include "command/request.hpp"
#include "geo/wgs84.hpp"
#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/packets.hpp"
#include "protocols/orion/orion_commands.hpp"

using namespace gimbal;
using nlohmann::json;

namespace {

struct Planned {
    std::optional<command::Error> error;
    command::Plan plan;
};

Planned plan(const std::string& cmd, json request, command::OrionContext ctx = {}) {
    Planned p;
    p.error = command::plan_orion(cmd, request, ctx, p.plan);
    return p;
}

// Decodes the single frame of a plan as packet type P.
template <class P>
P only_packet(const command::Plan& plan) {
    REQUIRE(plan.packets.size() == 1);
    orion::Framer framer;
    const auto frames = framer.push(plan.packets[0].frame);
    REQUIRE(frames.size() == 1);
    REQUIRE(frames[0].id == P::id);
    CHECK(plan.packets[0].sent == json{{"id", P::id}, {"len", frames[0].payload.size}});
    auto decoded = orion::decode<P>(frames[0].data());
    REQUIRE(decoded.ok);
    return decoded.value;
}

void require_error(const Planned& p, const std::string& code, const std::string& mentions) {
    REQUIRE(p.error);
    CHECK(p.error->code == code);
    CHECK_THAT(p.error->message, Catch::Contains(mentions));
    CHECK(p.plan.packets.empty());
    CHECK_FALSE(p.plan.laser);
}

constexpr double deg = orion::pi / 180.0;

}  // namespace

TEST_CASE("geopoint writes all 21 bytes of GeopointCmd", "[command][geopoint]") {
    auto p = plan("geopoint", {{"cmd", "geopoint"},
                               {"lat", 45.7},
                               {"lon", -121.5},
                               {"alt", 300},
                               {"vel_ned", {1.5, -2.25, 0.5}},
                               {"joystick_range_m", 250},
                               {"stare", true},
                               {"closure", true},
                               {"id", 7}});
    REQUIRE_FALSE(p.error);
    const auto cmd = only_packet<orion::GeopointCmd>(p.plan);
    CHECK(p.plan.packets[0].sent["len"] == 21);
    CHECK(cmd.target_lat / deg == Approx(45.7).margin(1e-7));
    CHECK(cmd.target_lon / deg == Approx(-121.5).margin(1e-7));
    CHECK(cmd.target_alt == Approx(300.0));
    CHECK(cmd.target_vel_ned[1] == Approx(-2.25));
    CHECK(cmd.joystick_range_m == 250);
    CHECK(cmd.options == orion::GeopointOptions::stare_closure);
    // The first data bytes are lat in 1e-7 degrees, big-endian: 457000000 = 0x1B3D4440.
    const auto& f = p.plan.packets[0].frame;
    CHECK(std::vector<std::uint8_t>(f.begin() + 4, f.begin() + 8) ==
          std::vector<std::uint8_t>{0x1B, 0x3D, 0x44, 0x40});
}

TEST_CASE("geopoint alt_ref msl adds the geoid undulation from telemetry", "[command][geopoint]") {
    const json request{{"lat", 45.7}, {"lon", -121.5}, {"alt", 300}, {"alt_ref", "msl"}};
    require_error(plan("geopoint", request), "unavailable", "geoid");
    command::OrionContext ctx;
    ctx.geoid_undulation_m = -21.5;
    auto p = plan("geopoint", request, ctx);
    REQUIRE_FALSE(p.error);
    CHECK(only_packet<orion::GeopointCmd>(p.plan).target_alt == Approx(278.5));
}

TEST_CASE("geopoint refuses bad parameters and sends nothing", "[command][geopoint]") {
    require_error(plan("geopoint", {{"lat", 91}, {"lon", 0}, {"alt", 0}}), "out_of_range", "lat");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", -180.5}, {"alt", 0}}), "out_of_range",
                  "lon");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}}), "bad_request", "alt");
    require_error(plan("geopoint", {{"lat", "45"}, {"lon", 0}, {"alt", 0}}), "bad_request", "lat");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"altitude", 3}}),
                  "bad_request", "altitude");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"alt_ref", "agl"}}),
                  "bad_request", "alt_ref");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"vel_ned", {1, 2}}}),
                  "bad_request", "vel_ned");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"vel_ned", {1, 2, 400}}}),
                  "out_of_range", "vel_ned");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"joystick_range_m", 1.5}}),
                  "bad_request", "joystick_range_m");
    require_error(
        plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"joystick_range_m", 70000}}),
        "out_of_range", "joystick_range_m");
    require_error(plan("geopoint", {{"lat", 0}, {"lon", 0}, {"alt", 0}, {"stare", 1}}),
                  "bad_request", "stare");
}

TEST_CASE("path converts points to ECEF and is 5 + 9 x points long", "[command][path]") {
    json points = json::array();
    for (int i = 0; i < 3; ++i)
        points.push_back({{"lat", 45.7 + 0.01 * i}, {"lon", -121.5}, {"alt", 100.0 * i}});
    auto p = plan(
        "path",
        {{"points", points}, {"along_step_deg", 10}, {"cross_steps", 3}, {"cross_ratio", 1.5}});
    REQUIRE_FALSE(p.error);
    const auto path = only_packet<orion::Path>(p.plan);
    CHECK(p.plan.packets[0].sent["len"] == 5 + 9 * 3);
    REQUIRE(path.points.size() == 3);
    const auto ecef = geo::lla_to_ecef({45.72, -121.5, 200.0});
    CHECK(path.points[2].pos_ecef[0] == Approx(std::round(ecef.x)));
    CHECK(path.points[2].pos_ecef[2] == Approx(std::round(ecef.z)));
    CHECK(path.num_cross_track_steps == 3);
    CHECK(path.along_track_step_angle / deg == Approx(10.0).margin(0.01));
    CHECK(path.cross_track_step_ratio == Approx(1.5).margin(0.01));
    CHECK_FALSE(path.point_down);
}

TEST_CASE("path down takes no points", "[command][path]") {
    auto p = plan("path", {{"down", true}});
    REQUIRE_FALSE(p.error);
    const auto path = only_packet<orion::Path>(p.plan);
    CHECK(path.point_down);
    CHECK(path.points.empty());
    CHECK(p.plan.packets[0].sent["len"] == 5);
    require_error(
        plan("path", {{"down", true}, {"points", {{{"lat", 0}, {"lon", 0}, {"alt", 0}}}}}),
        "bad_request", "down");
    require_error(plan("path", json::object()), "bad_request", "points");
}

TEST_CASE("path refuses bad points", "[command][path]") {
    json many = json::array();
    for (int i = 0; i < 16; ++i) many.push_back({{"lat", 1}, {"lon", 1}, {"alt", 1}});
    require_error(plan("path", {{"points", many}}), "out_of_range", "15");
    require_error(plan("path", {{"points", json::array()}}), "bad_request", "points");
    require_error(plan("path", {{"points", {{{"lat", 1}, {"lon", 1}}}}}), "bad_request",
                  "points[0]");
    require_error(plan("path", {{"points", {{{"lat", 1}, {"lon", 1}, {"alt", 1}, {"x", 1}}}}}),
                  "bad_request", "'x'");
    require_error(plan("path", {{"points", {{{"lat", 100}, {"lon", 1}, {"alt", 1}}}}}),
                  "out_of_range", "points[0]");
    require_error(plan("path", {{"down", true}, {"cross_steps", 16}}), "out_of_range",
                  "cross_steps");
    require_error(plan("path", {{"down", true}, {"along_step_deg", 181}}), "out_of_range",
                  "along_step_deg");
}

TEST_CASE("laser safety rules of section 4.2", "[command][laser]") {
    const json fire{{"enable", true}, {"arm", true}, {"fire", true}};
    SECTION("fire is forbidden unless laser.allow_fire") {
        require_error(plan("laser", fire), "forbidden", "allow_fire");
    }
    command::OrionContext allowed;
    allowed.allow_fire = true;
    SECTION("fire needs enable and arm in the same command") {
        require_error(plan("laser", {{"enable", true}, {"arm", false}, {"fire", true}}, allowed),
                      "bad_request", "arm");
        require_error(plan("laser", {{"enable", false}, {"arm", true}, {"fire", true}}, allowed),
                      "bad_request", "enable");
    }
    SECTION("safety bypass is forbidden unless allowed") {
        json bypass = fire;
        bypass["safety_bypass"] = true;
        require_error(plan("laser", bypass, allowed), "forbidden", "allow_safety_bypass");
        allowed.allow_safety_bypass = true;
        auto p = plan("laser", bypass, allowed);
        REQUIRE_FALSE(p.error);
        CHECK(only_packet<orion::LaserCmd>(p.plan).safety_bypass);
    }
    SECTION("enable, arm and fire are required") {
        require_error(plan("laser", {{"enable", true}, {"arm", true}}, allowed), "bad_request",
                      "fire");
    }
    SECTION("a permitted fire plans the packet and its cease-fire") {
        json request = fire;
        request["index"] = 1;
        request["password"] = "secret";
        request["on_ms"] = 100;
        request["off_ms"] = 900;
        request["prf_code"] = 1111;
        auto p = plan("laser", request, allowed);
        REQUIRE_FALSE(p.error);
        const auto cmd = only_packet<orion::LaserCmd>(p.plan);
        CHECK(p.plan.packets[0].sent["len"] == 14 + 6);
        CHECK(cmd.index == 1);
        CHECK(cmd.password == "secret");
        CHECK(cmd.fire);
        CHECK(cmd.on_time_ms == 100);
        CHECK(cmd.prf_code == 1111);
        REQUIRE(p.plan.laser);
        CHECK(p.plan.laser->fire);
        CHECK(p.plan.laser->index == 1);
        orion::Framer framer;
        const auto cease = framer.push(p.plan.laser->cease_frame);
        REQUIRE(cease.size() == 1);
        const auto ceased = orion::decode<orion::LaserCmd>(cease[0].data());
        REQUIRE(ceased.ok);
        CHECK_FALSE(ceased.value.fire);
        CHECK(ceased.value.enable);
        CHECK(ceased.value.password == "secret");
    }
    SECTION("ranges") {
        require_error(
            plan("laser", {{"enable", true}, {"arm", true}, {"fire", false}, {"index", 2}}),
            "out_of_range", "index");
        require_error(plan("laser", {{"enable", true},
                                     {"arm", true},
                                     {"fire", false},
                                     {"password", "0123456789abcdef"}}),
                      "out_of_range", "password");
    }
}

TEST_CASE("position, rate and mode write OrionCmd", "[command][cmd]") {
    auto p = plan("position", {{"pan", 90}, {"tilt", -45}, {"impulse_time_s", 2.5}});
    REQUIRE_FALSE(p.error);
    auto cmd = only_packet<orion::Cmd>(p.plan).cmd;
    CHECK(cmd.mode == orion::Mode::position);
    CHECK(cmd.target[0] / deg == Approx(90).margin(0.1));
    CHECK(cmd.target[1] / deg == Approx(-45).margin(0.1));
    CHECK_FALSE(cmd.stabilized);
    CHECK(cmd.impulse_time_s == Approx(2.5));

    p = plan("rate", {{"pan", 10}, {"tilt", 5}});
    REQUIRE_FALSE(p.error);
    cmd = only_packet<orion::Cmd>(p.plan).cmd;
    CHECK(cmd.mode == orion::Mode::rate);
    CHECK(cmd.stabilized);

    p = plan("mode", {{"mode", "ffc_auto"}});
    REQUIRE_FALSE(p.error);
    cmd = only_packet<orion::Cmd>(p.plan).cmd;
    CHECK(cmd.mode == orion::Mode::ffc_auto);
    CHECK(cmd.target == std::array<double, 2>{0, 0});

    // center: position 0, 0 in the aircraft's frame, whatever was held before.
    p = plan("center", json::object());
    REQUIRE_FALSE(p.error);
    cmd = only_packet<orion::Cmd>(p.plan).cmd;
    CHECK(cmd.mode == orion::Mode::position);
    CHECK(cmd.target == std::array<double, 2>{0, 0});
    CHECK_FALSE(cmd.stabilized);
    require_error(plan("center", {{"pan", 10}}), "bad_request", "pan");

    require_error(plan("mode", {{"mode", "geopoint"}}), "bad_request", "mode");
    require_error(plan("position", {{"pan", 181}, {"tilt", 0}}), "out_of_range", "pan");
    require_error(plan("rate", {{"pan", 0}, {"tilt", 5000}}), "out_of_range", "tilt");
    require_error(plan("position", {{"pan", 0}, {"tilt", 0}, {"impulse_time_s", 26}}),
                  "out_of_range", "impulse_time_s");
}

TEST_CASE("stare_ack echoes the latest StareStart by default", "[command][stare]") {
    require_error(plan("stare_ack", json::object()), "unavailable", "StareStart");
    command::OrionContext ctx;
    ctx.last_stare_time_ms = 123456;
    auto p = plan("stare_ack", json::object(), ctx);
    REQUIRE_FALSE(p.error);
    CHECK(only_packet<orion::StareAck>(p.plan).echo_system_time_ms == 123456);
    p = plan("stare_ack", {{"system_time_ms", 42}}, ctx);
    REQUIRE_FALSE(p.error);
    CHECK(only_packet<orion::StareAck>(p.plan).echo_system_time_ms == 42);
}

TEST_CASE("envelope: the reply shapes and the first checks", "[command][envelope]") {
    auto err = command::parse_request("not json");
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "bad_json");
    err = command::parse_request("[1,2]");
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "bad_json");
    err = command::parse_request(std::string(9000, ' '));
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "too_large");
    // Still JSON, but over the limit: refused unread (contract section 14;
    // test_request_limits.cpp).
    const std::string big = R"({"cmd": "ping", "id": 9, "pad": ")" + std::string(8200, 'x') + "\"}";
    err = command::parse_request(big);
    REQUIRE_FALSE(err);
    CHECK(err.error().code == "too_large");
    const json no_cmd = {{"id", "a1"}};
    auto refused = command::read_envelope(no_cmd);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == "unknown_cmd");
    CHECK(*command::echo_of(no_cmd).id == "a1");
    const json fly = {{"cmd", "fly"}, {"id", 3}};
    refused = command::read_envelope(fly);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().code == "unknown_cmd");
    const auto echo = command::echo_of(fly);
    CHECK(*echo.cmd == "fly");
    const auto reply = command::error_reply(echo.id, echo.cmd, refused.error());
    CHECK(reply["id"] == 3);
    CHECK(reply["ok"] == false);
    CHECK(reply["cmd"] == "fly");
    CHECK(reply["error"]["code"] == "unknown_cmd");

    const auto env = command::parse_request(R"({"cmd": "ping", "id": {"x": [1]}, "gimbal": "a"})");
    REQUIRE(env);
    CHECK(env->cmd() == "ping");
    CHECK(*env->gimbal == "a");
    const auto ok = command::ok_reply(env->id, env->cmd(), env->gimbal, {{"pong", true}});
    CHECK(
        ok ==
        json{{"id", {{"x", {1}}}}, {"ok", true}, {"cmd", "ping"}, {"gimbal", "a"}, {"pong", true}});
}

TEST_CASE("retract, camera and range commands", "[command]") {
    auto p = plan("retract", {{"action", "deploy"}});
    REQUIRE_FALSE(p.error);
    CHECK(only_packet<orion::RetractCommand>(p.plan).cmd == orion::RetractCmd::deploy);
    require_error(plan("retract", {{"action", "stow"}}), "bad_request", "action");

    p = plan("camera_switch", {{"index", 1}});
    REQUIRE_FALSE(p.error);
    CHECK(only_packet<orion::CameraSwitch>(p.plan).index == 1);
    require_error(plan("camera_switch", json::object()), "bad_request", "index");
    require_error(plan("camera_switch", {{"index", 256}}), "out_of_range", "index");

    p = plan("camera_zoom", {{"zoom", 2.5}});
    REQUIRE_FALSE(p.error);
    const auto zoom = only_packet<orion::CameraState>(p.plan);
    CHECK(zoom.zoom == Approx(2.5));
    CHECK(zoom.focus == Approx(-1.0));
    CHECK(zoom.index == 0);
    require_error(plan("camera_zoom", {{"zoom", 2}, {"iris", 1}}), "bad_request", "iris");

    p = plan("range", {{"range_m", 1234.5}, {"max_age_ms", 500}, {"source", "laser"}});
    REQUIRE_FALSE(p.error);
    const auto range = only_packet<orion::RangeData>(p.plan);
    CHECK(range.range_m == Approx(1234.5));
    CHECK(range.max_age_ms == 500);
    CHECK(range.source == orion::RangeSource::laser);
    require_error(plan("range", {{"range_m", -1}}), "out_of_range", "range_m");
    require_error(plan("range", {{"range_m", 10}, {"source", "radar"}}), "bad_request", "source");
}

TEST_CASE("request sends zero-length packets", "[command][request]") {
    auto p = plan("request", {{"packet", "versions"}});
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 6);
    CHECK(p.plan.packets[1].frame == orion::request_bytes(orion::pkt::crown_version));
    CHECK(p.plan.packets[1].sent == json{{"id", 40}, {"len", 0}});

    p = plan("request", {{"packet", "cameras"}});
    REQUIRE_FALSE(p.error);
    REQUIRE(p.plan.packets.size() == 1);
    CHECK(p.plan.packets[0].frame == orion::request_bytes(orion::pkt::cameras));

    // Commands are never "requested": a zero-length command packet means something else.
    require_error(plan("request", {{"packet", "laser_cmd"}}), "bad_request", "packet");
    require_error(plan("request", {{"packet", "reset"}}), "bad_request", "packet");
    require_error(plan("request", {{"packet", 40}}), "bad_request", "packet");
}
