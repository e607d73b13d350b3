// JsonReader (state/reader.hpp): what JsonWriter wrote reads back into the same typed part
// through the same fields(); wrong types are refused, unknown keys ignored.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "state/reader.hpp"
#include "state/track_state.hpp"
#include "state/writer.hpp"

using nlohmann::json;
namespace state = gimbal::state;

namespace {

state::TrackState a_track() {
    state::TrackState t;
    t.id = 7;
    t.state = "lost";
    t.box = {-0.25, -0.125, 0.25, 0.125};
    t.centre = {0, 0};
    t.confidence = 0.312;
    t.ground = state::TrackGround{45.6973012, -121.4807403, 414.612};
    t.velocity = state::TrackVelocity{1.5, -2.25, 2.7, 303.6901};
    t.steer = true;
    t.frames = 4000000000ull;
    t.lost_frames = 12;
    t.started_utc = "2026-11-29T09:15:02.123Z";
    t.age_s = 81.5;
    return t;
}

}  // namespace

TEST_CASE("a written part reads back equal", "[state]") {
    const auto written = state::write(a_track());
    const auto read = state::read<state::TrackState>(written);
    REQUIRE(read);
    CHECK(state::write(*read) == written);
    CHECK(read->frames == 4000000000ull);
    CHECK(read->ground->lat == 45.6973012);
    CHECK(read->velocity->course == 303.6901);
}

TEST_CASE("null empties an optional part; absent keys keep their defaults", "[state]") {
    auto t = a_track();
    t.ground.reset();
    t.velocity.reset();
    json written = state::write(t);
    written.erase("age_s");
    written["from_a_newer_gimbald"] = {1, 2};
    const auto read = state::read<state::TrackState>(written);
    REQUIRE(read);
    CHECK_FALSE(read->ground);
    CHECK_FALSE(read->velocity);
    CHECK(read->age_s == 0);
    CHECK(read->id == 7);
}

TEST_CASE("a non-finite number was written as null and reads back as NaN", "[state]") {
    auto t = a_track();
    t.confidence = std::nan("");
    const auto written = json::parse(state::write(t).dump());  // as a recording holds it
    CHECK(written["confidence"].is_null());
    const auto read = state::read<state::TrackState>(written);
    REQUIRE(read);
    CHECK(std::isnan(read->confidence));
}

TEST_CASE("wrong types and out-of-range integers are refused", "[state]") {
    const auto written = state::write(a_track());
    const auto refused = [&](const char* key, json value) {
        json j = written;
        j[key] = std::move(value);
        INFO(j.dump());
        CHECK_FALSE(state::read<state::TrackState>(j));
    };
    refused("id", "7");
    refused("id", -1);
    refused("id", 4294967296ull);  // beyond the u32 id
    refused("id", 1.5);
    refused("state", 1);
    refused("steer", 1);
    refused("confidence", "high");
    refused("box", json::array());
    refused("ground", 45.7);
    json bad_ground = written;
    bad_ground["ground"]["lat"] = "north";
    CHECK_FALSE(state::read<state::TrackState>(bad_ground));
    CHECK_FALSE(state::read<state::TrackState>(json::array()));
    CHECK_FALSE(state::read<state::TrackState>(json("text")));
}
