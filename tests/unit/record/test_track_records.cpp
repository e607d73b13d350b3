// The visual track in a recording (record/track_records.hpp, track_stream.hpp): the records
// gimbald writes, byte for byte; reading them back; picking interface track:<gimbal> out of
// a recording, across sections and files, skipping what is no track record.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pcapng_builder.hpp"
#include "record/track_records.hpp"
#include "record/track_stream.hpp"
#include "state/writer.hpp"

namespace r = gimbal::record;
namespace st = gimbal::state;
using gimbal::test::Builder;
using gimbal::test::Bytes;

namespace {

st::TrackState located() {
    st::TrackState t;
    t.id = 3;
    t.state = "tracking";
    t.box = {-0.05, -0.0625, 0.05, 0.0625};
    t.centre = {0, 0};
    t.confidence = 0.93;
    t.ground = st::TrackGround{45.697301, -121.48074, 414.6};
    t.velocity = st::TrackVelocity{0.12, -0.05, 0.13, 292.6199};
    t.steer = true;
    t.frames = 31;
    t.lost_frames = 0;
    t.started_utc = "2026-11-29T09:15:02.123Z";
    t.age_s = 2.07;
    return t;
}

std::span<const std::uint8_t> bytes_of(const std::string& s) {
    return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

Bytes pdu(const std::string& text, const std::string& dissector = "gimbald-json") {
    return Builder::exported_pdu(dissector, Bytes(text.begin(), text.end()));
}

const std::string lost_event = R"({"type":"event","gimbal":"main","event":"track_lost","id":3})";

}  // namespace

TEST_CASE("track records as gimbald writes them", "[record]") {
    CHECK(r::track_state_record("main", located()) ==
          R"({"gimbal":"main","state":{"track":{"age_s":2.07,"box":{"x0":-0.05,"x1":0.05,)"
          R"("y0":-0.0625,"y1":0.0625},"centre":{"x":0.0,"y":0.0},"confidence":0.93,)"
          R"("frames":31,"ground":{"alt":414.6,"lat":45.697301,"lon":-121.48074},)"
          R"("id":3,"lost_frames":0,"started_utc":"2026-11-29T09:15:02.123Z","state":"tracking",)"
          R"("steer":true,"velocity":{"course":292.6199,"east":-0.05,"north":0.12,"speed":0.13}}},)"
          R"("type":"state"})");
    CHECK(r::track_event_record(
              "main", {"track_end",
                       {{"id", 3}, {"reason", "timeout"}, {"frames", 40}, {"lost_frames", 9}}}) ==
          R"({"event":"track_end","frames":40,"gimbal":"main","id":3,"lost_frames":9,)"
          R"("reason":"timeout","type":"event"})");
    CHECK(r::is_track_event("track_reacquired"));
    CHECK_FALSE(r::is_track_event("link"));
}

TEST_CASE("track records read back", "[record]") {
    const auto state_record =
        r::read_track_record(bytes_of(r::track_state_record("main", located())), 1764072000123456);
    REQUIRE(state_record);
    CHECK(state_record->time_us == 1764072000123456);
    CHECK(state_record->gimbal == "main");
    const auto* t = std::get_if<st::TrackState>(&state_record->what);
    REQUIRE(t);
    CHECK(st::write(*t) == st::write(located()));

    const auto event_record = r::read_track_record(bytes_of(lost_event), 5);
    REQUIRE(event_record);
    const auto* e = std::get_if<r::TrackEvent>(&event_record->what);
    REQUIRE(e);
    CHECK(e->event == "track_lost");
    CHECK(e->id == 3);
    CHECK_FALSE(e->reason);

    const auto start = r::read_track_record(
        bytes_of(R"({"type":"event","gimbal":"main","event":"track_start","id":4,)"
                 R"("box":{"x0":-0.1,"y0":-0.1,"x1":0.1,"y1":0.1},"steer":false,"new_key":[]})"),
        6);
    REQUIRE(start);
    const auto& s = std::get<r::TrackEvent>(start->what);
    REQUIRE(s.box);
    CHECK(s.box->x1 == 0.1);
    CHECK(s.steer == false);
}

TEST_CASE("what is no track record is refused", "[record]") {
    for (const std::string text :
         {"", "not json", "[1,2]", R"({"type":"event","gimbal":"main","event":"link","id":3})",
          R"({"type":"event","gimbal":"main","event":"track_lost"})",
          R"({"type":"event","gimbal":"main","event":"track_lost","id":"3"})",
          R"({"type":"state","gimbal":"main","state":{"track":null}})",
          R"({"type":"state","gimbal":"main","state":{"telemetry":{}}})",
          R"({"type":"state","gimbal":"main","state":{"track":{"id":3,"ground":"x"}}})",
          R"({"type":"reply","ok":true})", R"({"gimbal":"main","event":"track_lost","id":3})"}) {
        INFO(text);
        CHECK_FALSE(r::read_track_record(bytes_of(text), 0));
    }
}

TEST_CASE("a gimbal's track interface picked out of a recording", "[record]") {
    const auto state_text = r::track_state_record("main", located());
    Builder b(false);
    b.shb()
        .idb("gimbal:main", 6, 252, 0, "orion tcp 127.0.0.1:8747")
        .idb("json")
        .idb("video:main")
        .idb("track:main")
        .idb("track:nose");
    b.epb(0, 10, pdu("x", "orion"), 1);
    b.epb(3, 11, pdu(lost_event), 2);
    b.epb(4, 12, pdu(state_text), 2);           // another gimbal's track
    b.epb(3, 13, pdu("garbage"), 2);            // not a record: counted
    b.epb(3, 14, {0x00, 0x0C, 0x00, 0x40}, 2);  // malformed tags: counted
    // A rotated file appended: a new section, the interfaces in another order.
    b.shb().idb("track:main").idb("gimbal:main", 6, 252, 0, "orion tcp 127.0.0.1:8747");
    b.epb(0, 20, pdu(state_text), 2);
    const auto file = b.out;

    r::TrackStream s;
    std::string error;
    REQUIRE(r::load_track_stream(file, "main", s, error));
    CHECK(s.found);
    CHECK(s.unreadable == 2);
    REQUIRE(s.records.size() == 2);
    CHECK(s.records[0].time_us == 11);
    CHECK(std::holds_alternative<r::TrackEvent>(s.records[0].what));
    CHECK(s.records[1].time_us == 20);
    CHECK(std::holds_alternative<st::TrackState>(s.records[1].what));

    r::TrackStream none;
    REQUIRE(r::load_track_stream(file, "tail", none, error));
    CHECK_FALSE(none.found);
    CHECK(none.records.empty());

    CHECK_FALSE(r::load_track_stream(Bytes{1, 2, 3}, "main", none, error));
    CHECK_FALSE(error.empty());
}

TEST_CASE("track records of several files, a cut one among them", "[record]") {
    const auto dir =
        std::filesystem::temp_directory_path() / ("track_stream_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto write = [&](const std::string& name, const Bytes& bytes) {
        std::ofstream(dir / name, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()),
                   static_cast<std::streamsize>(bytes.size()));
        return (dir / name).string();
    };
    Builder first(false);
    first.shb().idb("gimbal:main").idb("track:main");
    first.epb(1, 1, pdu(lost_event), 2);
    first.epb(1, 2, pdu(lost_event), 2);
    first.out.resize(first.out.size() - 3);  // cut inside its last block
    Builder second(false);
    second.shb().idb("gimbal:main").idb("track:main");
    second.epb(1, 3, pdu(lost_event), 2);
    Builder untracked(false);
    untracked.shb().idb("gimbal:main");

    r::TrackStream s;
    std::string error;
    REQUIRE(r::load_track_files({write("a.pcapng", first.out), write("b.pcapng", second.out),
                                 write("c.pcapng", untracked.out)},
                                "main", s, error));
    CHECK(s.found);
    REQUIRE(s.records.size() == 2);
    CHECK(s.records[0].time_us == 1);
    CHECK(s.records[1].time_us == 3);

    CHECK_FALSE(r::load_track_files({(dir / "missing.pcapng").string()}, "main", s, error));
    CHECK(error.find("missing.pcapng: ") != std::string::npos);
    std::filesystem::remove_all(dir);
}
