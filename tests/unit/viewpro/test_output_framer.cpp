// The gimbal-output framer: what a serial port delivers is split frames, junk, false FE
// starts and corrupted bytes, so that is what these tests feed it.
#include <catch2/catch.hpp>
#include <random>

#include "framer_harness.hpp"
#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/output.hpp"
#include "protocols/viewpro/codec/output_framer.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using namespace viewpro_test;

namespace {

using Harness = FramerHarness<OutputFramer>;

// One frame of each format from the ICD and the tables, plus random content of each format.
std::vector<Bytes> sample_frames(std::uint32_t seed) {
    std::vector<Bytes> frames{icd_out1, golden_out2, golden_out3, golden_out4};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(-180, 180);
    for (const OutFormat f : {OutFormat::out1, OutFormat::out2, OutFormat::out3, OutFormat::out4}) {
        Output o;
        o.format = f;
        o.time = DateTime{2024, 5, 6, 7, 8, 9};
        o.zoom = static_cast<std::uint16_t>(rng());
        o.gimbal_roll_deg = angle(rng);
        o.gimbal_pitch_deg = angle(rng);
        o.gimbal_yaw_deg = angle(rng);
        o.lrf_m = angle(rng) + 200;
        o.uav_roll_deg = angle(rng);
        o.uav_pitch_deg = angle(rng);
        o.uav_yaw_deg = angle(rng);
        o.uav_lat_deg = angle(rng) / 2;
        o.uav_lon_deg = angle(rng);
        o.uav_alt_msl_m = angle(rng) * 10;
        o.target_lat_deg = angle(rng) / 2;
        o.target_lon_deg = angle(rng);
        o.target_alt_msl_m = angle(rng);
        frames.push_back(encode_output(o));
    }
    return frames;
}

bool valid_output_at(const Bytes& stream, std::size_t i) {
    for (const std::size_t len : {out1_size, out2_size, out3_size})
        if (i + len <= stream.size() &&
            make_output_frame(std::span(stream).subspan(i, len)).has_value())
            return true;
    return false;
}

OutFormat format_of(const Bytes& frame) {
    const auto f = make_output_frame(frame);
    REQUIRE(f);
    return f->format;
}

}  // namespace

TEST_CASE("output framer delivers every frame split at every byte offset",
          "[viewpro][framer][output]") {
    check_split_at_every_offset<OutputFramer>(sample_frames(1));
}

TEST_CASE("output framer delivers a stream split at every pair of offsets",
          "[viewpro][framer][output]") {
    check_stream_split_everywhere<OutputFramer>(sample_frames(2));
}

TEST_CASE("output framer finds every frame between junk, in order",
          "[viewpro][framer][output][junk]") {
    check_frames_between_junk<OutputFramer>(
        sample_frames(3), Bytes{output_header, out1_id, out2_id, out3_id, out4_flag},
        valid_output_at, 20240611);
}

TEST_CASE("output framer tells OUT3 from OUT4 and reports each format",
          "[viewpro][framer][output]") {
    Harness h;
    OutputFramer framer;
    std::vector<OutFormat> formats;
    framer.push(concat({icd_out1, golden_out2, golden_out3, golden_out4}),
                [&](const OutputFrame& f) { formats.push_back(f.format); });
    CHECK(formats == std::vector<OutFormat>{OutFormat::out1, OutFormat::out2, OutFormat::out3,
                                            OutFormat::out4});
    CHECK(format_of(golden_out3) == OutFormat::out3);
    CHECK(format_of(golden_out4) == OutFormat::out4);
}

TEST_CASE("a stray FE before a frame costs one byte", "[viewpro][framer][output]") {
    SECTION("in the same push") {
        Harness h;
        h.push(concat({{output_header}, golden_out3}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == golden_out3);
        CHECK(h.framer.stats().dropped_bytes == 1);
        CHECK(h.framer.stats().bad_checksums == 0);  // FE FE: no id, not a checksum failure
    }
    SECTION("alone at the end of a push") {
        Harness h;
        h.push(Bytes{0x55, output_header});
        CHECK(h.framer.pending_bytes() == 1);  // might be the start of a frame
        h.push(icd_out1);
        REQUIRE(h.got.size() == 1);
        CHECK(h.framer.stats().dropped_bytes == 2);
        CHECK(h.counters_consistent());
    }
}

// A false header claims a length; the real frame sits inside the bytes it claims. The framer
// re-scans from the byte after the false start, so the real frame is not lost.
TEST_CASE("a false FE start does not lose the frame inside it",
          "[viewpro][framer][output][false-start]") {
    for (const std::uint8_t id : {out1_id, out2_id, out3_id}) {
        CAPTURE(int{id});
        const Bytes stream = concat({{output_header, id}, golden_out3, icd_out1, golden_out2});
        for (const std::size_t chunk : {stream.size(), std::size_t{1}, std::size_t{7}}) {
            CAPTURE(chunk);
            Harness h;
            h.push_in_chunks(stream, chunk);
            REQUIRE(h.got.size() == 3);
            CHECK(h.got[0] == golden_out3);
            CHECK(h.got[1] == icd_out1);
            CHECK(h.got[2] == golden_out2);
            CHECK(h.framer.stats().dropped_bytes == 2);
            CHECK(h.framer.stats().bad_checksums == 1);
            CHECK(h.counters_consistent());
        }
    }
}

TEST_CASE("a frame inside a false frame waits only until the false one can be checked",
          "[viewpro][framer][output][false-start]") {
    Harness h;
    h.push(concat({{output_header, out2_id}, icd_out1}));  // false OUT2 claims 76 bytes
    CHECK(h.got.empty());
    h.push(Bytes(out2_size - 2 - icd_out1.size(), 0x00));  // now the false frame is complete
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == icd_out1);
    CHECK(h.framer.stats().bad_checksums == 1);
    CHECK(h.counters_consistent());
}

TEST_CASE("a bad checksum is counted and the next frame delivered", "[viewpro][framer][output]") {
    for (const std::size_t flip : {std::size_t{2}, std::size_t{9}, std::size_t{22}}) {
        CAPTURE(flip);
        Bytes bad = icd_out1;
        bad[flip] ^= 0x40;
        Harness h;
        h.push(concat({bad, golden_out4}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == golden_out4);
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.framer.stats().dropped_bytes == bad.size());
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("an unknown id after FE is skipped without a checksum count",
          "[viewpro][framer][output]") {
    for (const int id : {0x00, 0xFA, 0xFE, 0xFF}) {
        Harness h;
        h.push(concat({{output_header, static_cast<std::uint8_t>(id)}, golden_out3}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.framer.stats().bad_checksums == 0);
        CHECK(h.framer.stats().dropped_bytes == 2);
    }
}

TEST_CASE("output reset() forgets a partial frame", "[viewpro][framer][output]") {
    Harness h;
    h.push(std::span(golden_out2).first(30));
    CHECK(h.framer.pending_bytes() == 30);
    h.framer.reset();
    CHECK(h.framer.pending_bytes() == 0);
    CHECK(h.framer.stats().dropped_bytes == 30);
    h.push(std::span(golden_out2).subspan(30));  // the rest is now junk
    h.push(golden_out2);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == golden_out2);
    CHECK(h.framer.stats().dropped_bytes == golden_out2.size());
    CHECK(h.counters_consistent());
}

TEST_CASE("output push() can return the frames as a vector", "[viewpro][framer][output]") {
    OutputFramer f;
    const auto out = f.push(concat({golden_out4, {0x00}, icd_out1}));
    REQUIRE(out.size() == 2);
    CHECK(out[0].format == OutFormat::out4);
    CHECK(Bytes(out[0].view().begin(), out[0].view().end()) == golden_out4);
    CHECK(out[1].format == OutFormat::out1);
    CHECK(f.stats().dropped_bytes == 1);
    CHECK(f.stats().frames == 2);
    CHECK(f.stats().bytes == golden_out4.size() + 1 + icd_out1.size());
}
