// A request parsed once (command/request.hpp): the limits before the one parse and the
// envelope; and its parameters read by JsonParams (command/params.hpp) against the catalogue
// - every type's checks with the contract's messages, the ranges the catalogue's.
#include <catch2/catch.hpp>

#include <string>

#include "command/catalogue.hpp"
#include "command/params.hpp"
#include "command/request.hpp"

namespace command = gimbal::command;
using gimbal::ErrorCode;
using nlohmann::json;

namespace {

// The error reading `doc`'s envelope, "ok" when it reads.
std::string refusal(const json& doc) {
    const auto r = command::read_envelope(doc);
    return r ? "ok" : std::string(to_string(r.error().code)) + ": " + r.error().message;
}

// The error reading every parameter of `doc` (its command's, in the catalogue's order, none
// required) and then refusing unknown ones; "ok" when all read.
std::string param_refusal(const json& doc) {
    const std::string cmd = doc.at("cmd");
    command::JsonParams p(doc, cmd);
    for (const command::ParamSpec& spec : command::find_command(cmd)->params) {
        switch (spec.type) {
            case command::ParamType::number:
                p.number(spec.name, false);
                break;
            case command::ParamType::integer:
                p.integer(spec.name, false);
                break;
            case command::ParamType::boolean:
                p.boolean(spec.name, false);
                break;
            case command::ParamType::choice:
                p.choice(spec.name, false);
                break;
            case command::ParamType::text:
                p.text(spec.name, false);
                break;
            case command::ParamType::numbers:
                p.numbers(spec.name, false);
                break;
            default:
                p.raw(spec.name);
                break;
        }
    }
    p.reject_unknown();
    return p.ok() ? "ok" : std::string(to_string(p.error().code)) + ": " + p.error().message;
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
          "[command][params]") {
    const json geopoint = {{"cmd", "geopoint"}, {"lat", 45.7}, {"lon", -121.5}, {"alt", 100}};
    CHECK(param_refusal(geopoint) == "ok");
    CHECK(param_refusal(with(geopoint, "lat", 91)) ==
          "out_of_range: 'lat' must be between -90 and 90");
    CHECK(param_refusal(with(geopoint, "lat", "45")) == "bad_request: 'lat' must be a number");
    CHECK(param_refusal(with(geopoint, "alt", -2001)) ==
          "out_of_range: 'alt' must be between -2000 and 100000");
    CHECK(param_refusal(with(geopoint, "joystick_range_m", 1.5)) ==
          "bad_request: 'joystick_range_m' must be an integer");
    CHECK(param_refusal(with(geopoint, "joystick_range_m", 70000)) ==
          "out_of_range: 'joystick_range_m' must be between 0 and 65535");
    CHECK(param_refusal(with(geopoint, "stare", 1)) ==
          "bad_request: 'stare' must be true or false");
    CHECK(param_refusal(with(geopoint, "alt_ref", "agl")) ==
          "bad_request: 'alt_ref' must be one of wgs84, msl, terrain");
    CHECK(param_refusal(with(geopoint, "vel_ned", {1, 2})) ==
          "bad_request: 'vel_ned' must be an array of 3 numbers");
    CHECK(param_refusal(with(geopoint, "vel_ned", {1, 2, 400})) ==
          "out_of_range: 'vel_ned' items must be between -327.67 and 327.67");
    CHECK(param_refusal(with(geopoint, "altitude_ref", "msl")) ==
          "bad_request: unknown parameter 'altitude_ref'");
    // null is absent.
    CHECK(param_refusal(with(geopoint, "vel_ned", nullptr)) == "ok");

    const json laser = {{"cmd", "laser"}, {"enable", false}, {"arm", false}, {"fire", false}};
    CHECK(param_refusal(with(laser, "password", std::string(16, 'p'))) ==
          "out_of_range: 'password' must be at most 15 characters");
    CHECK(param_refusal(with(laser, "password", "tab\there")) ==
          "bad_request: 'password' must be printable ASCII");
    CHECK(param_refusal(with(laser, "password", 5)) == "bad_request: 'password' must be a string");
    CHECK(param_refusal({{"cmd", "stare_ack"}, {"system_time_ms", 4294967296.0}}) ==
          "out_of_range: 'system_time_ms' must be between 0 and 4294967295");
    // Another command's range for the same key: a rate's pan is not a position's.
    CHECK(param_refusal({{"cmd", "position"}, {"pan", 181}}) ==
          "out_of_range: 'pan' must be between -180 and 180");
    CHECK(param_refusal({{"cmd", "rate"}, {"pan", 181}}) == "ok");
    CHECK(param_refusal({{"cmd", "ping"}, {"verbose", true}}) ==
          "bad_request: unknown parameter 'verbose'");
}

TEST_CASE("parameters: required is the reader's, and a key the catalogue lacks is a bug",
          "[command][params]") {
    const json position = {{"cmd", "position"}, {"pan", 10}, {"tilt", -30.5}};
    command::JsonParams p(position, "position");
    CHECK(p.number("pan", true) == 10.0);
    CHECK(p.number_or("impulse_time_s", 0.5) == 0.5);
    CHECK(p.boolean_or("stabilized", true));
    CHECK(p.ok());
    // A planner reading a parameter its command does not declare: internal, named.
    CHECK_FALSE(p.number("lat", false));
    REQUIRE_FALSE(p.ok());
    CHECK(p.error().code == ErrorCode::internal);
    CHECK(p.error().message == "parameter 'lat' is not in the catalogue of 'position'");

    command::JsonParams missing({{"cmd", "geopoint"}, {"lon", 1}}, "geopoint");
    CHECK_FALSE(missing.number("lat", true));
    CHECK(missing.error().message == "missing parameter 'lat'");
}

TEST_CASE("parameters: a path point read against the catalogue's fields", "[command][params]") {
    const json path = {{"cmd", "path"}, {"points", {{{"lat", 95}, {"lon", 0}}}}};
    command::JsonParams p(path, "path");
    const auto fields = p.fields_of("points");
    REQUIRE(fields.size() == 3);
    command::JsonParams point(path["points"][0], fields);
    CHECK_FALSE(point.number("lat", true));
    CHECK(point.error().message == "'lat' must be between -90 and 90");
}
