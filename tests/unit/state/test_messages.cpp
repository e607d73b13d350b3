#include <catch2/catch.hpp>

#include "state/messages.hpp"

using gimbal::state::parse_state_keys;
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

TEST_CASE("parse_state_keys accepts known names and rejects the rest with the name") {
    std::vector<std::string> keys;
    CHECK(parse_state_keys(json{"telemetry", "lasers", "telemetry"}, keys).empty());
    CHECK(keys == std::vector<std::string>{"telemetry", "lasers"});
    CHECK(parse_state_keys(json::array(), keys).empty());
    CHECK(keys.empty());
    CHECK(parse_state_keys(json{"telemetry", "telemtry"}, keys).find("'telemtry'") !=
          std::string::npos);
    CHECK_FALSE(parse_state_keys(json("telemetry"), keys).empty());
    CHECK_FALSE(parse_state_keys(json{1, 2}, keys).empty());
}

TEST_CASE("state and event messages have the datagram shape of section 4.1") {
    CHECK(gimbal::state::state_message("main", json{{"stale", true}}) ==
          json{{"type", "state"}, {"gimbal", "main"}, {"state", {{"stale", true}}}});
    const gimbal::state::Event e{"link", {{"connected", false}}};
    CHECK(gimbal::state::event_message("nose", e) ==
          json{{"type", "event"}, {"gimbal", "nose"}, {"event", "link"}, {"connected", false}});
}
