// The framer gets what a serial port or a busy link delivers: frames split anywhere, junk and
// stray 55 bytes between them, cut-off headers, corrupted lengths and CRCs.
#include <catch2/catch.hpp>
#include <random>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "vectors.hpp"

using namespace gimbal::siyi;
using namespace siyi_test;

namespace {

struct Harness {
    Framer framer;
    std::vector<Bytes> got;  // the bytes of each delivered frame
    std::uint64_t delivered_bytes = 0;

    void push(std::span<const std::uint8_t> bytes) {
        framer.push(bytes, [&](const Frame& f) {
            got.push_back(frame_bytes(f));
            delivered_bytes += f.wire_size();
        });
    }
    void push(const Bytes& bytes) { push(std::span<const std::uint8_t>(bytes)); }
    void push_in_chunks(const Bytes& stream, std::size_t chunk) {
        for (std::size_t at = 0; at < stream.size(); at += chunk)
            push(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
    }
    // Every byte pushed is in a delivered frame, dropped, or waiting.
    bool consistent() const {
        const auto& s = framer.stats();
        return s.bytes == delivered_bytes + s.dropped_bytes + framer.pending_bytes() &&
               s.frames == got.size();
    }
};

// The SDK's examples, a documented reply, a captured reply and frames of every length class
// up to the longest allowed.
std::vector<Bytes> sample_frames() {
    std::vector<Bytes> frames;
    for (const Golden& g : sdk_requests()) frames.push_back(g.bytes);
    frames.push_back(mk15_hardware_id_reply);
    frames.push_back(captured_attitude_reply);
    Bytes data(max_data_length);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(0x55 + i);
    frames.push_back(frame_bytes(Header{ctrl_ack_pack, 0x6655}, 0x66, data));
    frames.push_back(frame_bytes(Header{0x00, 0xFFFF}, 0x55, {}));
    return frames;
}

bool valid_frame_at(const Bytes& stream, std::size_t i) {
    if (i + header_size > stream.size() || stream[i] != stx0 || stream[i + 1] != stx1) return false;
    const std::size_t len = stream[i + 3] | (std::size_t{stream[i + 4]} << 8);
    if (len > max_data_length || i + frame_overhead + len > stream.size()) return false;
    return make_frame(std::span(stream).subspan(i, frame_overhead + len)).has_value();
}

}  // namespace

TEST_CASE("framer delivers every frame split at every byte offset", "[siyi][framer]") {
    for (const Bytes& frame : sample_frames()) {
        for (std::size_t cut = 0; cut <= frame.size(); ++cut) {
            CAPTURE(frame.size(), cut);
            Harness h;
            h.push(std::span(frame).first(cut));
            CHECK(h.got.empty() == (cut < frame.size()));
            h.push(std::span(frame).subspan(cut));
            REQUIRE(h.got.size() == 1);
            CHECK(h.got[0] == frame);
            CHECK(h.framer.stats().dropped_bytes == 0);
            CHECK(h.framer.pending_bytes() == 0);
            CHECK(h.consistent());
        }
    }
}

TEST_CASE("framer delivers a stream of frames split at every pair of offsets", "[siyi][framer]") {
    std::vector<Bytes> frames;
    for (const Golden& g : sdk_requests()) frames.push_back(g.bytes);
    frames.push_back(captured_attitude_reply);
    const Bytes stream = concat(frames);
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        for (std::size_t cut2 = cut; cut2 <= stream.size(); cut2 += 1 + cut2 % 17) {
            Harness h;
            h.push(std::span(stream).first(cut));
            h.push(std::span(stream).subspan(cut, cut2 - cut));
            h.push(std::span(stream).subspan(cut2));
            REQUIRE(h.got == frames);
            REQUIRE(h.framer.stats().dropped_bytes == 0);
            REQUIRE(h.consistent());
        }
    }
}

TEST_CASE("framer finds every frame between junk, in order", "[siyi][framer][junk]") {
    const std::vector<Bytes> frames = sample_frames();
    std::mt19937 rng(20250226);
    const Bytes special{stx0, stx1, 0x01, 0x02, 0x00, 0x0D};
    auto junk_byte = [&]() -> std::uint8_t {
        return rng() % 2 ? special[rng() % special.size()] : static_cast<std::uint8_t>(rng());
    };
    Bytes stream;
    std::vector<Bytes> want;
    std::vector<std::pair<std::size_t, std::size_t>> junk_ranges;
    std::uint64_t junk_total = 0;
    for (int n = 0; n < 3000; ++n) {
        const std::size_t junk_len = rng() % 24;
        junk_ranges.emplace_back(stream.size(), stream.size() + junk_len);
        for (std::size_t i = 0; i < junk_len; ++i) stream.push_back(junk_byte());
        junk_total += junk_len;
        const Bytes& f = frames[rng() % frames.size()];
        stream.insert(stream.end(), f.begin(), f.end());
        want.push_back(f);
    }
    // A clean tail longer than any frame lets every false start resolve.
    while (stream.size() - junk_ranges.back().second < 2 * max_frame_size) {
        stream.insert(stream.end(), frames[0].begin(), frames[0].end());
        want.push_back(frames[0]);
    }
    // Junk that happens to hold a real frame would be one: break its start.
    for (bool clean = false; !clean;) {
        clean = true;
        for (const auto& [begin, end] : junk_ranges)
            for (std::size_t i = begin; i < end; ++i)
                if (valid_frame_at(stream, i)) {
                    stream[i] = 0x00;
                    clean = false;
                }
    }

    Harness h;
    for (std::size_t at = 0; at < stream.size();) {
        const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 200);
        h.push(std::span(stream).subspan(at, n));
        at += n;
        REQUIRE(h.consistent());
    }
    REQUIRE(h.got.size() == want.size());
    CHECK(h.got == want);
    CHECK(h.framer.stats().dropped_bytes == junk_total);
    CHECK(h.framer.stats().bad_checksums > 0);  // the junk did contain false starts
    CHECK(h.framer.stats().oversize > 0);
    CHECK(h.framer.pending_bytes() == 0);
}

TEST_CASE("a stray 55 before a frame costs one byte", "[siyi][framer]") {
    const Bytes& frame = sdk_requests()[10].bytes;  // one-key centering
    SECTION("in the same push") {
        Harness h;
        h.push(concat({{stx0}, frame}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == frame);
        CHECK(h.framer.stats().dropped_bytes == 1);
        CHECK(h.framer.stats().bad_checksums == 0);  // 55 55: no frame, not a CRC failure
    }
    SECTION("alone at the end of a push") {
        Harness h;
        h.push(Bytes{0x12, stx0});
        CHECK(h.framer.pending_bytes() == 1);  // might be the start of a frame
        h.push(frame);
        REQUIRE(h.got.size() == 1);
        CHECK(h.framer.stats().dropped_bytes == 2);
        CHECK(h.consistent());
    }
}

// A false header claims a length; real frames sit inside the bytes it claims. The framer
// re-scans from the byte after the false start, so none is lost - where a parser that resumes
// after the whole false frame (as ArduPilot's does) loses them.
TEST_CASE("a false 55 66 start does not lose the frames inside it", "[siyi][framer][false-start]") {
    const Bytes& a = sdk_requests()[10].bytes;
    const Bytes& b = captured_attitude_reply;
    const Bytes false_header = hex("55 66 01 20 00 00 00 0D");  // claims 32 bytes
    const Bytes stream = concat({false_header, a, b, hex("00 00 00 00 00 00 00 00 00 00 00 00")});
    for (const std::size_t chunk : {stream.size(), std::size_t{1}, std::size_t{5}}) {
        CAPTURE(chunk);
        Harness h;
        h.push_in_chunks(stream, chunk);
        REQUIRE(h.got.size() == 2);
        CHECK(h.got[0] == a);
        CHECK(h.got[1] == b);
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.framer.stats().dropped_bytes == false_header.size() + 12);
        CHECK(h.consistent());
    }
}

TEST_CASE("a cut-off header before a frame does not lose the frame", "[siyi][framer]") {
    const Bytes& frame = captured_attitude_reply;
    for (std::size_t cut = 1; cut < header_size; ++cut) {
        CAPTURE(cut);
        const Bytes stream = concat({Bytes(frame.begin(), frame.begin() + static_cast<long>(cut)),
                                     frame, Bytes(frame.size(), 0x00)});
        Harness h;
        h.push_in_chunks(stream, 3);
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == frame);
        CHECK(h.consistent());
    }
}

TEST_CASE("a wrong CRC is counted and the next frame delivered", "[siyi][framer]") {
    const Bytes& good = sdk_requests()[3].bytes;  // absolute zoom 4.5
    for (std::size_t flip = 2; flip < good.size(); ++flip) {
        CAPTURE(flip);
        Bytes bad = good;
        bad[flip] ^= 0x01;
        Harness h;
        h.push(concat({bad, good, Bytes(max_frame_size, 0x00)}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == good);
        CHECK(h.framer.stats().bad_checksums + h.framer.stats().oversize >= 1);
        CHECK(h.consistent());
    }
    // The CRC trailer itself wrong, either byte.
    for (const std::size_t at : {good.size() - 2, good.size() - 1}) {
        Bytes bad = good;
        bad[at] ^= 0x80;
        CHECK_FALSE(make_frame(bad));
        Harness h;
        h.push(concat({bad, good}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.framer.stats().dropped_bytes == bad.size());
    }
}

TEST_CASE("a length over the longest frame is a false sync at once", "[siyi][framer]") {
    const Bytes& good = sdk_requests()[10].bytes;
    const Bytes oversize = hex("55 66 01 81 00 00 00 0D");  // 129 > max_data_length
    Harness h;
    h.push(concat({oversize, good}));
    REQUIRE(h.got.size() == 1);  // not held back waiting for 129 bytes
    CHECK(h.framer.stats().oversize == 1);
    CHECK(h.framer.stats().dropped_bytes == oversize.size());
    CHECK(h.consistent());
    CHECK_FALSE(make_frame(hex("55 66 01 FF FF 00 00 0D")));
}

TEST_CASE("a truncated frame waits, and reset() forgets it", "[siyi][framer]") {
    const Bytes& frame = sdk_requests()[26].bytes;  // the 42-byte GPS frame
    Harness h;
    h.push(std::span(frame).first(30));
    CHECK(h.got.empty());
    CHECK(h.framer.pending_bytes() == 30);
    h.framer.reset();
    CHECK(h.framer.pending_bytes() == 0);
    CHECK(h.framer.stats().dropped_bytes == 30);
    h.push(std::span(frame).subspan(30));  // the rest is now junk
    h.push(frame);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == frame);
    CHECK(h.framer.stats().dropped_bytes == frame.size());
    CHECK(h.consistent());
    // Exactly one frame, not a prefix or more.
    CHECK_FALSE(make_frame(std::span(frame).first(frame.size() - 1)));
    CHECK_FALSE(make_frame(concat({frame, {0x00}})));
    CHECK_FALSE(make_frame({}));
}

TEST_CASE("push() can return the frames as a vector", "[siyi][framer]") {
    Framer f;
    const auto out = f.push(concat({captured_attitude_reply, {0x00}, mk15_hardware_id_reply}));
    REQUIRE(out.size() == 2);
    CHECK(out[0].cmd == cmd::gimbal_attitude);
    CHECK(out[0].seq == 6);
    CHECK(out[0].data.size == 12);
    CHECK(out[1].cmd == 0x40);
    CHECK(f.stats().dropped_bytes == 1);
    CHECK(f.stats().frames == 2);
}
