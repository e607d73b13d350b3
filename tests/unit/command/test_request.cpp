// A request parsed once and read against the catalogue (command/request.hpp): the limits
// before the one parse, the envelope, and every parameter type's checks with the contract's
// messages - the ranges are the catalogue's.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "command/catalogue.hpp"
#include "command/request.hpp"

namespace command = gimbal::command;
using gimbal::ErrorCode;
using nlohmann::json;

namespace {

// The error reading `doc` as a request, "ok" when it reads.
std::string refusal(const json& doc) {
    const auto r = command::read_request(doc);
    return r ? "ok" : std::string(to_string(r.error().code)) + ": " + r.error().message;
}

json with(json doc, const std::string& key, json value) {
    doc[key] = std::move(value);
    return doc;
}

}  // namespace

TEST_CASE("parse_request: the limits on the raw bytes, then one parse", "[command][request]") {
    auto before = command::request_parses();
    auto r = command::parse_request(R"({"cmd":"ping","id":7,"gimbal":"a","token":"t"})");
    REQUIRE(r);
    CHECK(command::request_parses() == before + 1);
    CHECK(r->cmd() == "ping");
    CHECK(r->id == json(7));
    CHECK(r->gimbal == "a");
    CHECK(r->token == "t");

    // Over the limits: refused unparsed.
    before = command::request_parses();
    auto big = command::parse_request(R"({"cmd":"ping","pad":")" + std::string(9000, 'x') + "\"}");
    REQUIRE_FALSE(big);
    CHECK(big.error().code == ErrorCode::too_large);
    auto deep = command::parse_request(R"({"cmd":"ping","id":)" + std::string(40, '[') +
                                       std::string(40, ']') + "}");
    REQUIRE_FALSE(deep);
    CHECK(deep.error().code == ErrorCode::bad_json);
    CHECK(command::request_parses() == before);

    for (const char* text : {"not json", "[1,2]", "\"text\"", ""}) {
        INFO(text);
        const auto bad = command::parse_request(text);
        REQUIRE_FALSE(bad);
        CHECK(bad.error().code == ErrorCode::bad_json);
        CHECK(bad.error().message == "the datagram is not a JSON object");
    }
}

TEST_CASE("the envelope: cmd from the catalogue, gimbal and token strings", "[command][request]") {
    CHECK(refusal({{"id", 1}}) == "unknown_cmd: missing 'cmd'");
    CHECK(refusal({{"cmd", 5}}) == "unknown_cmd: 'cmd' must be a string");
    CHECK(refusal({{"cmd", "fly"}}) == "unknown_cmd: unknown command 'fly'");
    CHECK(refusal({{"cmd", "ping"}, {"gimbal", 5}}) == "bad_request: 'gimbal' must be a string");
    CHECK(refusal({{"cmd", "ping"}, {"token", true}}) == "bad_request: 'token' must be a string");
    CHECK(refusal({{"cmd", "ping"}, {"gimbal", nullptr}, {"token", nullptr}}) == "ok");
    // A signed payload's ts and nonce are the envelope's, not parameters.
    CHECK(refusal({{"cmd", "ping"}, {"ts", 1}, {"nonce", "abcdefgh"}}) == "ok");

    // What a refusal still echoes.
    auto echo = command::echo_of({{"cmd", "fly"}, {"id", {{"x", 1}}}});
    CHECK(echo.id == json{{"x", 1}});
    CHECK(echo.cmd == "fly");
    echo = command::echo_of({{"cmd", 5}});
    CHECK_FALSE(echo.id);
    CHECK_FALSE(echo.cmd);
    echo = command::echo_of(json::array());
    CHECK_FALSE(echo.cmd);
}

TEST_CASE("parameters: the catalogue's types and ranges, named in the message",
          "[command][request]") {
    const json geopoint = {{"cmd", "geopoint"}, {"lat", 45.7}, {"lon", -121.5}, {"alt", 100}};
    CHECK(refusal(geopoint) == "ok");
    CHECK(refusal(with(geopoint, "lat", 91)) == "out_of_range: 'lat' must be between -90 and 90");
    CHECK(refusal(with(geopoint, "lat", "45")) == "bad_request: 'lat' must be a number");
    CHECK(refusal(with(geopoint, "alt", -2001)) ==
          "out_of_range: 'alt' must be between -2000 and 100000");
    CHECK(refusal(with(geopoint, "joystick_range_m", 1.5)) ==
          "bad_request: 'joystick_range_m' must be an integer");
    CHECK(refusal(with(geopoint, "joystick_range_m", 70000)) ==
          "out_of_range: 'joystick_range_m' must be between 0 and 65535");
    CHECK(refusal(with(geopoint, "stare", 1)) == "bad_request: 'stare' must be true or false");
    CHECK(refusal(with(geopoint, "alt_ref", "agl")) ==
          "bad_request: 'alt_ref' must be one of wgs84, msl, terrain");
    CHECK(refusal(with(geopoint, "vel_ned", {1, 2})) ==
          "bad_request: 'vel_ned' must be an array of 3 numbers");
    CHECK(refusal(with(geopoint, "vel_ned", {1, 2, 400})) ==
          "out_of_range: 'vel_ned' items must be between -327.67 and 327.67");
    CHECK(refusal(with(geopoint, "altitude_ref", "msl")) ==
          "bad_request: unknown parameter 'altitude_ref'");
    // The first problem in the catalogue's order wins; unknown keys come last.
    CHECK(refusal(with(with(geopoint, "lat", 91), "zz", 1)) ==
          "out_of_range: 'lat' must be between -90 and 90");
    CHECK(refusal(with(with(geopoint, "lon", 200), "lat", 91)) ==
          "out_of_range: 'lat' must be between -90 and 90");
    // null is absent.
    CHECK(refusal(with(geopoint, "vel_ned", nullptr)) == "ok");
    CHECK(refusal({{"cmd", "geopoint"}, {"lon", 1}}) == "bad_request: missing parameter 'lat'");

    const json laser = {{"cmd", "laser"}, {"enable", false}, {"arm", false}, {"fire", false}};
    CHECK(refusal(with(laser, "password", std::string(16, 'p'))) ==
          "out_of_range: 'password' must be at most 15 characters");
    CHECK(refusal(with(laser, "password", "tab\there")) ==
          "bad_request: 'password' must be printable ASCII");
    CHECK(refusal(with(laser, "password", 5)) == "bad_request: 'password' must be a string");
    CHECK(refusal({{"cmd", "stare_ack"}, {"system_time_ms", 4294967296.0}}) ==
          "out_of_range: 'system_time_ms' must be between 0 and 4294967295");

    CHECK(refusal({{"cmd", "state"}, {"keys", "telemetry"}}) ==
          "bad_request: 'keys' must be an array of STATE key names");
    CHECK(refusal({{"cmd", "state"}, {"keys", {"telemetry", 1}}}) ==
          "bad_request: 'keys' must be an array of STATE key names");
    CHECK(refusal({{"cmd", "ping"}, {"verbose", true}}) ==
          "bad_request: unknown parameter 'verbose'");
}

TEST_CASE("parameters: path points, each field checked and named", "[command][request]") {
    const json point = {{"lat", 45}, {"lon", 0}, {"alt", 0}};
    auto path = [](json points) { return json{{"cmd", "path"}, {"points", std::move(points)}}; };
    CHECK(refusal(path({point})) == "ok");
    CHECK(refusal(path({{{"lat", 45}, {"lon", 0}}})) == "ok");  // alt left to the terrain
    CHECK(refusal(path(json::array())) ==
          "bad_request: 'points' must be an array of 1 to 15 points");
    CHECK(refusal(path(json(std::vector<json>(16, point)))) ==
          "out_of_range: 'points' must hold 1 to 15 points");
    CHECK(refusal(path({point, 5})) == "bad_request: points[1] must be {\"lat\",\"lon\",\"alt\"}");
    CHECK(refusal(path({with(point, "lat", 95)})) ==
          "out_of_range: points[0]: 'lat' must be between -90 and 90");
    CHECK(refusal(path({{{"lon", 0}}})) == "bad_request: points[0]: missing parameter 'lat'");
    CHECK(refusal(path({with(point, "speed", 3)})) ==
          "bad_request: points[0]: unknown parameter 'speed'");

    const auto r = command::read_request(path({point, {{"lat", 1.5}, {"lon", 2.5}}}));
    REQUIRE(r);
    const auto points = r->params.points("points");
    REQUIRE(points);
    REQUIRE(points->size() == 2);
    CHECK((*points)[0].alt == 0.0);
    CHECK((*points)[1].lat == 1.5);
    CHECK_FALSE((*points)[1].alt);
}

TEST_CASE("Params: values without ranges; a parameter the command lacks is a bug",
          "[command][request]") {
    const auto r = command::read_request({{"cmd", "position"}, {"pan", 10}, {"tilt", -30.5}});
    REQUIRE(r);
    const auto& p = r->params;
    CHECK(p.number("pan") == 10.0);
    CHECK(p.number("tilt") == -30.5);
    CHECK_FALSE(p.has("stabilized"));
    CHECK(p.boolean_or("stabilized", true));
    CHECK(p.number_or("impulse_time_s", 0.5) == 0.5);
    CHECK(p.values() == json{{"pan", 10}, {"tilt", -30.5}});
    CHECK_THROWS_AS(p.number("lat"), std::logic_error);

    const auto laser = command::read_request(
        {{"cmd", "laser"}, {"index", 1.0}, {"enable", true}, {"arm", true}, {"fire", false}});
    REQUIRE(laser);
    CHECK(laser->params.integer("index") == 1);
    CHECK(laser->params.boolean("enable") == true);
    CHECK_FALSE(laser->params.text("password"));
}

TEST_CASE("Params::set: a value the daemon fills in meets the same checks", "[command][request]") {
    auto r = command::read_request({{"cmd", "geopoint"}, {"lat", 45.7}, {"lon", -121.5}});
    REQUIRE(r);
    CHECK_FALSE(r->params.has("alt"));
    REQUIRE(r->params.set("alt", 512.5));
    CHECK(r->params.number("alt") == 512.5);
    const auto beyond = r->params.set("alt", 100001.0);
    REQUIRE_FALSE(beyond);
    CHECK(beyond.error().code == ErrorCode::out_of_range);
    CHECK(beyond.error().message == "'alt' must be between -2000 and 100000");
    CHECK(r->params.number("alt") == 512.5);  // a refused value changes nothing
    REQUIRE(r->params.set("alt_ref", "wgs84"));
    CHECK(r->params.choice("alt_ref") == "wgs84");
}

TEST_CASE("make_request: an adapter's request through the same checks, no text",
          "[command][request]") {
    const auto before = command::request_parses();
    auto r = command::make_request("rate", {{"pan", 5}, {"tilt", 0}}, "main");
    REQUIRE(r);
    CHECK(r->cmd() == "rate");
    CHECK(r->gimbal == "main");
    CHECK(command::request_object(*r) ==
          json{{"cmd", "rate"}, {"gimbal", "main"}, {"pan", 5}, {"tilt", 0}});
    const auto bad = command::make_request("rate", {{"pan", 5000}, {"tilt", 0}});
    REQUIRE_FALSE(bad);
    CHECK(bad.error().code == ErrorCode::out_of_range);
    CHECK_FALSE(command::make_request("warp", json::object()));
    CHECK(command::request_parses() == before);
}
