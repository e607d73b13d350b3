#include <catch2/catch.hpp>

#include "state/messages.hpp"

using gimbal::state::read_state_keys;
using gimbal::state::select_keys;
using nlohmann::json;

TEST_CASE("select_keys keeps the asked keys and always protocol, link and stale") {
    const json state = {{"protocol", "orion"}, {"link", {{"connected", true}}},
                        {"stale", false},      {"telemetry", {{"lat", 1.5}}},
                        {"gps", nullptr},      {"ins", 3}};
    const json only = select_keys(state, {"telemetry"});
    CHECK(only == json{{"protocol", "orion"},
                       {"link", {{"connected", true}}},
                       {"stale", false},
                       {"telemetry", {{"lat", 1.5}}}});
    CHECK(select_keys(state, {}) == state);
    // A key the gimbal does not have (a Viewpro's `output` on an Orion) is simply absent.
    CHECK(select_keys(state, {"output"}).size() == 3);
}

TEST_CASE("read_state_keys accepts known names and rejects the rest with the name") {
    auto keys = read_state_keys(json{"telemetry", "lasers", "telemetry"});
    REQUIRE(keys);
    CHECK(*keys == std::vector<std::string>{"telemetry", "lasers"});
    keys = read_state_keys(json::array());
    REQUIRE(keys);
    CHECK(keys->empty());
    keys = read_state_keys(json{"telemetry", "telemtry"});
    REQUIRE_FALSE(keys);
    CHECK(keys.error().code == gimbal::command::code::bad_request);
    CHECK(keys.error().message.find("'telemtry'") != std::string::npos);
    CHECK_FALSE(read_state_keys(json("telemetry")));
    CHECK_FALSE(read_state_keys(json{1, 2}));
}

TEST_CASE("state and event messages have the datagram shape of section 4.1") {
    CHECK(gimbal::state::state_message("main", json{{"stale", true}}) ==
          json{{"type", "state"}, {"gimbal", "main"}, {"state", {{"stale", true}}}});
    const gimbal::state::Event e{"link", {{"connected", false}}};
    CHECK(gimbal::state::event_message("nose", e) ==
          json{{"type", "event"}, {"gimbal", "nose"}, {"event", "link"}, {"connected", false}});
}

TEST_CASE("too_large_event names the size, the limit and the largest keys") {
    const json state = {{"protocol", "orion"},
                        {"video", {{"klv", std::string(5000, 'a')}}},
                        {"telemetry", {{"lat", std::string(300, 'b')}}},
                        {"link", {{"connected", true}}},
                        {"stale", false}};
    const json event = gimbal::state::too_large_event("main", 70000, 65507, state);
    CHECK(event["type"] == "event");
    CHECK(event["event"] == "too_large");
    CHECK(event["gimbal"] == "main");
    CHECK(event["bytes"] == 70000);
    CHECK(event["limit"] == 65507);
    // The three largest members with their size as JSON text, so the client knows what to
    // leave out with `keys`.
    REQUIRE(event["largest"].size() == 3);
    CHECK(event["largest"]["video"] == json(state["video"]).dump().size());
    CHECK(event["largest"]["telemetry"] == json(state["telemetry"]).dump().size());
    CHECK(event["largest"].contains("link"));
    const std::string message = event["message"];
    CHECK(message.find("70000 bytes") != std::string::npos);
    CHECK(message.find("'keys'") != std::string::npos);
    // Whatever it names, the notice itself is small.
    CHECK(event.dump().size() < 512);
    // Not an object (an event's own fields would be an object; a scalar has no members).
    CHECK(gimbal::state::too_large_event("main", 70000, 65507, json(3))["largest"].empty());
}
