// The simulator's framer of what a controller sends: IN1/IN2/IN3 and AA 55 commands, with
// splits, junk, false starts and bad checksums.
#include <catch2/catch.hpp>

#include "framer_harness.hpp"
#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/input_framer.hpp"
#include "protocols/viewpro/codec/mode.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using namespace viewpro_test;

namespace {

using Harness = FramerHarness<InputFramer>;
using Kind = InputFrame::Kind;

Bytes b5(const Command5& c) {
    return Bytes(c.begin(), c.end());
}

std::vector<Bytes> sample_frames() {
    return {golden_in1,
            golden_in2,
            golden_in3,
            icd_in2_example_40,
            b5(encode_mode(Mode{})),
            b5(encode_yaw_shift(-100)),
            b5(encode_pitch_shift(50)),
            b5(encode_mode(decode_mode_byte(0x01)))};
}

bool valid_input_at(const Bytes& stream, std::size_t i) {
    for (const std::size_t len : {command_size, in1_size, in2_size})
        if (i + len <= stream.size() &&
            make_input_frame(std::span(stream).subspan(i, len)).has_value())
            return true;
    return false;
}

}  // namespace

TEST_CASE("input framer delivers every frame split at every byte offset",
          "[viewpro][framer][input]") {
    check_split_at_every_offset<InputFramer>(sample_frames());
}

TEST_CASE("input framer delivers a stream split at every pair of offsets",
          "[viewpro][framer][input]") {
    check_stream_split_everywhere<InputFramer>(sample_frames());
}

TEST_CASE("input framer finds every frame between junk, in order",
          "[viewpro][framer][input][junk]") {
    check_frames_between_junk<InputFramer>(
        sample_frames(),
        Bytes{input_header, in1_id, in2_id, in3_flag, command_header0, command_header1, set_mode_id,
              yaw_shift_id, pitch_shift_id, command_end},
        valid_input_at, 77);
}

TEST_CASE("input framer reports each kind", "[viewpro][framer][input]") {
    InputFramer framer;
    std::vector<Kind> kinds;
    framer.push(concat(sample_frames()), [&](const InputFrame& f) { kinds.push_back(f.kind); });
    CHECK(kinds == std::vector<Kind>{Kind::in1, Kind::in2, Kind::in3, Kind::in2, Kind::mode,
                                     Kind::yaw_shift, Kind::pitch_shift, Kind::mode});
}

TEST_CASE("a command without its FF end is a bad checksum and costs one byte",
          "[viewpro][framer][input]") {
    const Bytes bad = hex("AA 55 0F 51 FE");
    const Bytes good = b5(encode_yaw_shift(100));
    Harness h;
    h.push(concat({bad, good}));
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == good);
    CHECK(h.framer.stats().bad_checksums == 1);
    CHECK(h.framer.stats().dropped_bytes == bad.size());
    CHECK(h.counters_consistent());
}

TEST_CASE("unknown commands and stray header bytes are dropped", "[viewpro][framer][input]") {
    Harness h;
    // AA alone, AA 55 with an unknown id, F9 with an unknown id, then a real IN1.
    h.push(concat({{command_header0}, hex("AA 55 07 00 FF"), hex("F9 FA"), golden_in1}));
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == golden_in1);
    CHECK(h.framer.stats().bad_checksums == 0);
    CHECK(h.framer.stats().dropped_bytes == 1 + 5 + 2);
    CHECK(h.counters_consistent());
}

TEST_CASE("a false F9 start does not lose the command inside it",
          "[viewpro][framer][input][false-start]") {
    // F9 FC claims 40 bytes; a mode command and an IN1 sit inside them.
    const Bytes mode = b5(encode_mode(Mode{}));
    const Bytes stream = concat({{input_header, in2_id}, mode, golden_in1, golden_in3});
    for (const std::size_t chunk : {stream.size(), std::size_t{1}, std::size_t{3}}) {
        CAPTURE(chunk);
        Harness h;
        h.push_in_chunks(stream, chunk);
        REQUIRE(h.got.size() == 3);
        CHECK(h.got[0] == mode);
        CHECK(h.got[1] == golden_in1);
        CHECK(h.got[2] == golden_in3);
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.framer.stats().dropped_bytes == 2);
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("a corrupted IN frame is counted and the next one delivered",
          "[viewpro][framer][input]") {
    Bytes bad = golden_in2;
    bad[25] ^= 0x10;
    Harness h;
    h.push(concat({bad, golden_in1}));
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == golden_in1);
    CHECK(h.framer.stats().bad_checksums == 1);
    CHECK(h.framer.stats().dropped_bytes == bad.size());
}

TEST_CASE("input reset() forgets a partial frame", "[viewpro][framer][input]") {
    Harness h;
    h.push(std::span(golden_in2).first(10));
    h.framer.reset();
    CHECK(h.framer.pending_bytes() == 0);
    CHECK(h.framer.stats().dropped_bytes == 10);
    h.push(golden_in3);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == golden_in3);
    const auto frames = InputFramer{}.push(golden_in3);
    REQUIRE(frames.size() == 1);
    CHECK(frames[0].kind == Kind::in3);
}
