// The object's track in gimbal-export: tracks built from recorded track records (written by
// the recorder's own functions and read back), their lines, lost stretches and marks, and
// the GeoJSON, KML and track-csv outputs checked against small golden texts.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "export/writers.hpp"
#include "record/track_records.hpp"

namespace fe = gimbal::flight_export;
namespace r = gimbal::record;
namespace st = gimbal::state;

namespace {

constexpr std::int64_t t0 = 1764072000000000;  // 2025-11-25T12:00:00Z

std::int64_t at_ms(int ms) {
    return t0 + ms * 1000LL;
}

st::TrackState box(std::uint32_t id, const char* state, std::optional<st::TrackGround> ground,
                   std::optional<st::TrackVelocity> velocity = std::nullopt) {
    st::TrackState t;
    t.id = id;
    t.state = state;
    t.box = {-0.1, -0.05, 0.1, 0.05};
    t.centre = {0, 0};
    t.confidence = std::string(state) == "lost" ? 0.25 : 0.9;
    t.ground = ground;
    t.velocity = velocity;
    t.started_utc = "2025-11-25T12:00:00.000Z";
    return t;
}

st::Event event(std::string kind, nlohmann::json fields) {
    return {std::move(kind), std::move(fields)};
}

// Each record as the recorder writes it, read back as gimbal-export reads it.
class Recording {
  public:
    Recording& state(int ms, const st::TrackState& t) {
        return add(ms, r::track_state_record("main", t));
    }
    Recording& event(int ms, const st::Event& e) {
        return add(ms, r::track_event_record("main", e));
    }
    r::TrackStream stream() const { return stream_; }

  private:
    Recording& add(int ms, const std::string& pdu) {
        auto record = r::read_track_record(
            {reinterpret_cast<const std::uint8_t*>(pdu.data()), pdu.size()}, at_ms(ms));
        REQUIRE(record);
        stream_.records.push_back(std::move(*record));
        return *this;
    }
    r::TrackStream stream_{"main", true, {}, 0};
};

// Track 1: started, located twice, lost (one predicted position), re-acquired, stopped.
// Track 2: its start not recorded (the recording began while it ran), two positions, no end.
r::TrackStream two_tracks() {
    const st::TrackGround a{45.6973, -121.4807, 414.6}, b{45.6974, -121.4806, 414.7},
        c{45.6975, -121.4805, 414.8}, d{45.6976, -121.4804, 414.9};
    const st::TrackVelocity v{11.12, 7.8, 13.58, 35.0};
    Recording rec;
    rec.event(0, event("track_start",
                       {{"id", 1},
                        {"box", {{"x0", -0.1}, {"y0", -0.05}, {"x1", 0.3}, {"y1", 0.05}}},
                        {"steer", true}}))
        .state(100, box(1, "tracking", std::nullopt))
        .state(200, box(1, "tracking", a))
        .state(300, box(1, "tracking", b, v))
        .event(350, event("track_lost", {{"id", 1}}))
        .state(400, box(1, "lost", c, v))
        .event(500, event("track_reacquired", {{"id", 1}}))
        .state(500, box(1, "tracking", d, v))
        .event(600, event("track_end",
                          {{"id", 1}, {"reason", "stopped"}, {"frames", 4}, {"lost_frames", 1}}))
        .state(5000, box(2, "tracking", a))
        .state(5100, box(2, "tracking", b));
    return rec.stream();
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("object tracks: one per track, split at track_start and at another id", "[export]") {
    const auto tracks = fe::object_tracks(two_tracks());
    REQUIRE(tracks.size() == 2);
    const auto& one = tracks[0];
    CHECK(one.id == 1);
    CHECK(one.gimbal == "main");
    CHECK(one.start_us == at_ms(0));
    CHECK(one.end_us == at_ms(600));
    CHECK(one.end_reason == "stopped");
    REQUIRE(one.samples.size() == 9);
    CHECK(one.samples[0].event == "track_start");
    CHECK(one.samples[0].state == "tracking");
    CHECK_FALSE(one.samples[1].ground);  // not located yet
    CHECK(one.samples[4].state == "lost");
    CHECK(one.samples[8].state == "ended");
    CHECK(one.samples[8].reason == "stopped");
    CHECK(fe::object_line(one).size() == 4);
    const auto& two = tracks[1];
    CHECK(two.id == 2);
    CHECK(two.start_us == at_ms(5000));
    CHECK_FALSE(two.end_reason);

    // A restarted gimbald numbers from 1 again: a new track_start is a new track.
    auto stream = two_tracks();
    stream.records.erase(stream.records.begin() + 8);  // track 1's end lost
    const auto restart = stream.records.front();
    stream.records.insert(stream.records.begin() + 8, restart);
    CHECK(fe::object_tracks(stream).size() == 3);
}

TEST_CASE("lost stretches span the gap; marks sit where the filter last had the object",
          "[export]") {
    const auto tracks = fe::object_tracks(two_tracks());
    const auto stretches = fe::lost_stretches(tracks[0]);
    REQUIRE(stretches.size() == 1);
    REQUIRE(stretches[0].size() == 3);  // the last seen, the predicted, the first seen again
    CHECK(stretches[0][0]->time_us == at_ms(300));
    CHECK(stretches[0][1]->state == "lost");
    CHECK(stretches[0][2]->time_us == at_ms(500));
    const auto marks = fe::object_marks(tracks[0]);
    REQUIRE(marks.size() == 3);  // lost, reacquired, end (start has no position yet)
    CHECK(marks[0].event->event == "track_lost");
    CHECK(marks[0].at.lat == 45.6974);
    CHECK(marks[1].event->event == "track_reacquired");
    CHECK(marks[1].at.lat == 45.6975);  // the prediction: the box with it came later
    CHECK(marks[2].event->event == "track_end");
    CHECK(marks[2].at.lat == 45.6976);
    CHECK(fe::lost_stretches(tracks[1]).empty());
}

TEST_CASE("track-csv: golden", "[export]") {
    const auto csv = fe::to_track_csv(fe::object_tracks(two_tracks()));
    CHECK(csv == read_text(GIMBAL_SOURCE_DIR "/tests/unit/export/golden/track.csv"));
}

TEST_CASE("track-csv: a number STATE wrote as null is an empty cell", "[export]") {
    auto t = box(4, "tracking", st::TrackGround{45.6973, -121.4807, std::nan("")});
    t.confidence = std::nan("");
    Recording rec;
    rec.state(0, t);
    const auto csv = fe::to_track_csv(fe::object_tracks(rec.stream()));
    CHECK(csv.substr(csv.find("\r\n") + 2) ==
          "2025-11-25T12:00:00.000Z,main,4,,tracking,45.6973,-121.4807,,,,,,,0,0,\r\n");
}

TEST_CASE("GeoJSON with the object's track: golden", "[export]") {
    fe::Flight flight;
    flight.gimbal = "main";
    flight.protocol = "orion";
    const auto text = fe::to_geojson(flight, 10, fe::object_tracks(two_tracks()));
    CHECK(text == read_text(GIMBAL_SOURCE_DIR "/tests/unit/export/golden/track.geojson"));
    CHECK_NOTHROW(nlohmann::json::parse(text));
}

TEST_CASE("KML with the object's track: golden, MSL heights from the aircraft's undulation",
          "[export]") {
    fe::Flight flight;
    flight.gimbal = "main";
    flight.protocol = "orion";
    // The aircraft's undulation: -20 m before 0.45 s, -21 m after.
    for (int ms : {0, 400, 450, 900}) {
        fe::TrackPoint p;
        p.time_us = at_ms(ms);
        p.aircraft = fe::Position{45.7, -121.5, 1500, ms < 450 ? 1520 : 1521};
        flight.points.push_back(p);
    }
    const auto text = fe::to_kml(flight, 10, fe::object_tracks(two_tracks()));
    CHECK(text == read_text(GIMBAL_SOURCE_DIR "/tests/unit/export/golden/track.kml"));

    // Without an undulation the object's lines are clamped to the ground.
    flight.points.clear();
    const auto clamped = fe::to_kml(flight, 10, fe::object_tracks(two_tracks()));
    CHECK(clamped.find("<altitudeMode>absolute</altitudeMode>") == std::string::npos);
    CHECK(clamped.find("<altitudeMode>clampToGround</altitudeMode><coordinates>-121.4807,45.6973 "
                       "-121.4806,45.6974") != std::string::npos);
}

TEST_CASE("no object tracks: the outputs are as before", "[export]") {
    fe::Flight flight;
    flight.gimbal = "main";
    CHECK(fe::to_kml(flight, 10, {}) == fe::to_kml(flight, 10));
    CHECK(fe::to_kml(flight, 10).find("object") == std::string::npos);
    CHECK(fe::to_track_csv({}) ==
          "time,gimbal,id,event,state,lat,lon,alt,velocity_north,velocity_east,speed,course,"
          "confidence,centre_x,centre_y,reason\r\n");
}
