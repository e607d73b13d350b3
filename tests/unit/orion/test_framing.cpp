// Framing (framing.hpp) and the streaming framer (framer.hpp): what a serial port delivers is
// split packets, junk, false syncs and corrupted bytes, so that is what these tests feed it.
#include <catch2/catch.hpp>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/codec/packets.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;

namespace {

// One frame as delivered, for comparing with what was sent.
struct Seen {
    std::uint8_t id;
    Bytes data;
    bool operator==(const Seen&) const = default;
};

Seen seen(const Frame& f) {
    return {f.id, Bytes(f.data().begin(), f.data().end())};
}

// The frame a wire frame should come out as.
Seen expected(const Bytes& wire) {
    return {wire[2], Bytes(wire.begin() + header_size, wire.end() - checksum_size)};
}

// A framer with everything it delivered.
struct Harness {
    Framer framer;
    std::vector<Seen> got;
    std::uint64_t delivered_bytes = 0;

    void push(std::span<const std::uint8_t> bytes) {
        framer.push(bytes, [&](const Frame& f) {
            got.push_back(seen(f));
            delivered_bytes += header_size + f.payload.size + checksum_size;
        });
    }
    void push(const Bytes& bytes) { push(std::span<const std::uint8_t>(bytes)); }

    // Every byte pushed is in a delivered frame, dropped, or waiting.
    bool counters_consistent() const {
        const FramerStats& s = framer.stats();
        return s.bytes == delivered_bytes + s.dropped_bytes + framer.pending_bytes() &&
               s.packets == got.size();
    }
};

Bytes concat(const std::vector<Bytes>& parts) {
    Bytes out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

// One full-size wire frame of every packet type with a layout, with varied content: random
// bytes decoded as that packet and encoded again (so every frame is what our encoder sends),
// plus the zero-length request form.
std::vector<Bytes> sample_frames(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<Bytes> frames;
    for_each_packet([&]<class P>() {
        Bytes data(P::max_length);
        for (auto& b : data) b = static_cast<std::uint8_t>(rng());
        P packet{};
        if (auto d = decode<P>(data)) packet = d.value;
        frames.push_back(to_wire(packet));
        frames.push_back(request_bytes(P::id));
    });
    return frames;
}

bool has_valid_checksum(const Bytes& frame) {
    if (frame.size() < header_size + checksum_size) return false;
    const std::uint16_t sum = fletcher251({frame.data(), frame.size() - checksum_size});
    return frame[frame.size() - 2] == (sum >> 8) && frame[frame.size() - 1] == (sum & 0xFF);
}

// Position of a sync candidate starting in [begin, end) of `stream` that is checksum-valid:
// random junk that happens to form a real frame is a real frame, and would spoil a count.
std::optional<std::size_t> frame_in_junk(const Bytes& stream, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end && i + header_size <= stream.size(); ++i) {
        if (stream[i] != sync0 || stream[i + 1] != sync1) continue;
        const std::size_t total = header_size + stream[i + 3] + checksum_size;
        if (stream[i + 3] > max_data_length || i + total > stream.size()) continue;
        if (has_valid_checksum(Bytes(stream.begin() + static_cast<long>(i),
                                     stream.begin() + static_cast<long>(i + total))))
            return i;
    }
    return std::nullopt;
}

}  // namespace

TEST_CASE("Fletcher-251 matches the ICD's reference vector", "[orion][checksum]") {
    const Bytes header{0xD0, 0x0D, 0x28, 0x00};
    CHECK(fletcher251(header) == 0x0BCA);
    CHECK(request_bytes(pkt::crown_version) == Bytes{0xD0, 0x0D, 0x28, 0x00, 0x0B, 0xCA});
}

TEST_CASE("Fletcher-251 equals the ICD's byte-by-byte reference", "[orion][checksum]") {
    // InitChecksum / UpdateChecksum from the ICD, modulo after every byte.
    auto reference = [](const Bytes& bytes) {
        std::uint16_t a = static_cast<std::uint16_t>((bytes[0] + 1) % 251);
        std::uint16_t b = a;
        for (std::size_t i = 1; i < bytes.size(); ++i) {
            a = static_cast<std::uint16_t>((a + bytes[i]) % 251);
            b = static_cast<std::uint16_t>((b + a) % 251);
        }
        return static_cast<std::uint16_t>((a << 8) | b);
    };
    std::mt19937 rng(7);
    for (int n = 1; n <= static_cast<int>(header_size + max_data_length); ++n) {
        Bytes bytes(static_cast<std::size_t>(n));
        for (auto& b : bytes) b = static_cast<std::uint8_t>(rng() | 0x80);  // large sums
        CHECK(fletcher251(bytes) == reference(bytes));
    }
    CHECK(fletcher251(Bytes(146, 0xFF)) == reference(Bytes(146, 0xFF)));
}

TEST_CASE("every packet type frames to a checksum-valid frame of its length", "[orion][framing]") {
    for (const Bytes& f : sample_frames(1)) {
        REQUIRE(f.size() >= header_size + checksum_size);
        CHECK(f[0] == sync0);
        CHECK(f[1] == sync1);
        CHECK(f[3] == f.size() - header_size - checksum_size);
        CHECK(has_valid_checksum(f));
    }
}

TEST_CASE("framer delivers every packet split at every byte offset", "[orion][framer]") {
    for (const Bytes& frame : sample_frames(2)) {
        for (std::size_t cut = 0; cut <= frame.size(); ++cut) {
            Harness h;
            h.push(std::span(frame).first(cut));
            CHECK(h.got.empty() == (cut < frame.size()));
            h.push(std::span(frame).subspan(cut));
            REQUIRE(h.got.size() == 1);
            CHECK(h.got[0] == expected(frame));
            CHECK(h.framer.stats().dropped_bytes == 0);
            CHECK(h.framer.pending_bytes() == 0);
            CHECK(h.counters_consistent());
        }
    }
}

TEST_CASE("framer delivers a stream of every packet split at every pair of offsets",
          "[orion][framer]") {
    const std::vector<Bytes> frames = sample_frames(3);
    const Bytes stream = concat(frames);
    std::vector<Seen> want;
    for (const Bytes& f : frames) want.push_back(expected(f));
    for (std::size_t cut = 0; cut <= stream.size(); cut += 1) {
        const std::size_t cut2 = std::min(stream.size(), cut + 1 + cut % 150);
        Harness h;
        h.push(std::span(stream).first(cut));
        h.push(std::span(stream).subspan(cut, cut2 - cut));
        h.push(std::span(stream).subspan(cut2));
        REQUIRE(h.got == want);
        CHECK(h.framer.stats().dropped_bytes == 0);
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("framer delivers a frame pushed one byte at a time", "[orion][framer]") {
    const std::vector<Bytes> frames = sample_frames(4);
    Harness h;
    std::size_t delivered = 0;
    for (const Bytes& f : frames) {
        for (std::size_t i = 0; i < f.size(); ++i) {
            h.push(std::span(f).subspan(i, 1));
            // Nothing comes out before the last byte, and the frame comes out on it.
            CHECK(h.got.size() == delivered + (i + 1 == f.size() ? 1 : 0));
        }
        ++delivered;
        CHECK(h.got.back() == expected(f));
        CHECK(h.framer.pending_bytes() == 0);
    }
    CHECK(h.framer.stats().dropped_bytes == 0);
    CHECK(h.counters_consistent());
}

TEST_CASE("framer finds every packet between random junk, in order", "[orion][framer][junk]") {
    const std::vector<Bytes> frames = sample_frames(5);
    std::mt19937 rng(20240611);
    // Junk rich in sync bytes, so false syncs and cut-off headers happen often.
    auto junk_byte = [&]() -> std::uint8_t {
        switch (rng() % 4) {
            case 0:
                return sync0;
            case 1:
                return sync1;
            default:
                return static_cast<std::uint8_t>(rng());
        }
    };
    Bytes stream;
    std::vector<Seen> want;
    std::vector<std::pair<std::size_t, std::size_t>> junk_ranges;
    std::uint64_t junk_total = 0;
    const int packets = 3000;
    for (int n = 0; n < packets; ++n) {
        const std::size_t junk_len = rng() % 24;
        junk_ranges.emplace_back(stream.size(), stream.size() + junk_len);
        for (std::size_t i = 0; i < junk_len; ++i) stream.push_back(junk_byte());
        junk_total += junk_len;
        const Bytes& f = frames[rng() % frames.size()];
        stream.insert(stream.end(), f.begin(), f.end());
        want.push_back(expected(f));
    }
    // A clean tail longer than any frame lets every false sync resolve.
    while (stream.size() - junk_ranges.back().second < 2 * max_frame_size) {
        stream.insert(stream.end(), frames[0].begin(), frames[0].end());
        want.push_back(expected(frames[0]));
    }
    // Junk that happens to form a checksum-valid frame would be one: break its sync.
    for (bool clean = false; !clean;) {
        clean = true;
        for (const auto& [begin, end] : junk_ranges)
            if (const auto at = frame_in_junk(stream, begin, end)) {
                stream[*at] = 0x00;
                clean = false;
            }
    }

    // Push in random chunk sizes, some larger than two frames.
    Harness h;
    for (std::size_t at = 0; at < stream.size();) {
        const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 400);
        h.push(std::span(stream).subspan(at, n));
        at += n;
        REQUIRE(h.counters_consistent());
    }
    REQUIRE(h.got.size() == want.size());
    CHECK(h.got == want);
    CHECK(h.framer.stats().dropped_bytes == junk_total);
    CHECK(h.framer.stats().packets == want.size());
    CHECK(h.framer.stats().bad_checksums > 0);  // the junk did contain false syncs
    CHECK(h.framer.pending_bytes() == 0);
}

TEST_CASE("a stray D0 before a valid packet costs one byte", "[orion][framer]") {
    const Bytes frame = frame_bytes(1, Bytes{1, 2, 3, 4, 5, 6, 7});
    SECTION("in the same push") {
        Harness h;
        h.push(concat({{sync0}, frame}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == expected(frame));
        CHECK(h.framer.stats().dropped_bytes == 1);
    }
    SECTION("alone at the end of a push") {
        Harness h;
        h.push(Bytes{0x55, sync0});
        CHECK(h.framer.pending_bytes() == 1);  // might be the start of a frame
        h.push(frame);
        REQUIRE(h.got.size() == 1);
        CHECK(h.framer.stats().dropped_bytes == 2);
        CHECK(h.counters_consistent());
    }
    SECTION("several, and a D0 0D D0 0D double sync") {
        // D0 0D + the frame's D0 0D reads as a header of length 13: resolved (as false) once
        // the second frame has arrived.
        Harness h;
        h.push(concat({{sync0, sync0, sync0}, {sync0, sync1}, frame, frame}));
        REQUIRE(h.got.size() == 2);
        CHECK(h.got[0] == expected(frame));
        CHECK(h.framer.stats().dropped_bytes == 5);
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.counters_consistent());
    }
}

// The reference SDK's byte parser skips a whole false frame after a failed checksum, losing
// the real packet that started inside it. Ours re-scans from the byte after the false sync.
TEST_CASE("a cut-off header does not lose the packet after it", "[orion][framer][false-sync]") {
    const std::vector<Bytes> frames = sample_frames(6);
    const Bytes& valid = frames[0];  // the first packet type, full length
    const Bytes tail = concat({frames[2], frames[4], frames[6], frames[0], frames[0]});
    for (const int len : {0, 1, 2, 5, 46, 89, 139, 140}) {
        CAPTURE(len);
        const Bytes cut_header{sync0, sync1, 212, static_cast<std::uint8_t>(len)};
        const Bytes stream = concat({cut_header, valid, tail});
        REQUIRE(stream.size() >= cut_header.size() + max_frame_size);
        REQUIRE_FALSE(frame_in_junk(stream, 0, 1));
        for (const std::size_t chunk : {stream.size(), std::size_t{1}, std::size_t{7}}) {
            CAPTURE(chunk);
            Harness h;
            for (std::size_t at = 0; at < stream.size(); at += chunk)
                h.push(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
            REQUIRE(h.got.size() == 6);
            CHECK(h.got[0] == expected(valid));
            CHECK(h.got[1] == expected(frames[2]));
            CHECK(h.framer.stats().dropped_bytes == cut_header.size());
            CHECK(h.framer.stats().bad_checksums >= 1);
            CHECK(h.counters_consistent());
        }
    }
}

TEST_CASE("a packet inside a false frame waits only until the false frame can be checked",
          "[orion][framer][false-sync]") {
    // The false header claims 140 bytes; the real 11-byte packet sits inside them. The framer
    // cannot know the false frame is false until its checksum bytes arrive.
    const Bytes valid = frame_bytes(1, Bytes{1, 2, 3, 4, 5, 6, 7});
    Harness h;
    h.push(concat({{sync0, sync1, 99, 140}, valid}));
    CHECK(h.got.empty());
    h.push(Bytes(140 + 2 - valid.size(), 0x00));  // enough bytes to complete the false frame
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == expected(valid));
    CHECK(h.framer.stats().bad_checksums == 1);
    CHECK(h.counters_consistent());
}

TEST_CASE("a corrupted length byte costs only that frame", "[orion][framer]") {
    const Bytes payload{0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A};
    const Bytes good = frame_bytes(42, payload);
    const std::vector<Bytes> others = sample_frames(7);
    for (const int delta : {-10, -3, -1, 1, 2, 30, 131}) {
        CAPTURE(delta);
        Bytes bad = good;
        bad[3] = static_cast<std::uint8_t>(bad[3] + delta);
        const Bytes stream = concat({bad, others[0], others[2], others[4]});
        Harness h;
        h.push(stream);
        REQUIRE(h.got.size() == 3);
        CHECK(h.got[0] == expected(others[0]));
        CHECK(h.framer.stats().dropped_bytes == bad.size());
        CHECK(h.counters_consistent());
        if (bad[3] > max_data_length)
            CHECK(h.framer.stats().oversize == 1);
        else
            CHECK(h.framer.stats().bad_checksums == 1);
    }
}

TEST_CASE("a bad checksum is counted and the next packet is delivered", "[orion][framer]") {
    const Bytes payload{0x11, 0x22, 0x33};
    for (const std::size_t flip :
         {std::size_t{2}, std::size_t{4}, std::size_t{7}, std::size_t{8}}) {
        CAPTURE(flip);  // id, data, either checksum byte
        Bytes bad = frame_bytes(5, payload);
        bad[flip] ^= 0x40;
        const Bytes next = frame_bytes(6, payload);
        Harness h;
        h.push(concat({bad, next}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == expected(next));
        CHECK(h.framer.stats().bad_checksums == 1);
        CHECK(h.framer.stats().dropped_bytes == bad.size());
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("a length over 140 is counted as oversize and skipped", "[orion][framer]") {
    const Bytes next = frame_bytes(6, Bytes{1, 2, 3});
    for (const int len : {141, 142, 200, 255}) {
        CAPTURE(len);
        Harness h;
        h.push(concat({{sync0, sync1, 7, static_cast<std::uint8_t>(len), 1, 2, 3}, next}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == expected(next));
        CHECK(h.framer.stats().oversize == 1);
        CHECK(h.framer.stats().dropped_bytes == 7);
        CHECK(h.counters_consistent());
    }
    // 140 itself is a legal length.
    Harness h;
    const Bytes longest = frame_bytes(9, Bytes(140, 0x5A));
    h.push(longest);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == expected(longest));
    CHECK(h.framer.stats().oversize == 0);
}

TEST_CASE("reset() forgets a partial frame", "[orion][framer]") {
    const Bytes frame = frame_bytes(1, Bytes{1, 2, 3, 4, 5, 6, 7});
    const std::size_t half = frame.size() / 2;
    Harness h;
    h.push(std::span(frame).first(half));
    CHECK(h.framer.pending_bytes() == half);
    h.framer.reset();
    CHECK(h.framer.pending_bytes() == 0);
    CHECK(h.framer.stats().dropped_bytes == half);
    CHECK(h.counters_consistent());
    // The rest of the old frame is now junk; the next whole frame still comes through.
    h.push(std::span(frame).subspan(half));
    h.push(frame);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == expected(frame));
    CHECK(h.framer.stats().dropped_bytes == frame.size());
    CHECK(h.counters_consistent());
    // reset() on an idle framer changes nothing.
    h.framer.reset();
    CHECK(h.framer.stats().dropped_bytes == frame.size());
}

TEST_CASE("push() can return the frames as a vector", "[orion][framer]") {
    const std::vector<Bytes> frames = sample_frames(8);
    Framer f;
    const std::vector<Frame> out = f.push(concat({frames[0], {0x00}, frames[1]}));
    REQUIRE(out.size() == 2);
    CHECK(seen(out[0]) == expected(frames[0]));
    CHECK(seen(out[1]) == expected(frames[1]));
    CHECK(f.stats().dropped_bytes == 1);
}
