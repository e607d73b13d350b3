// The streaming framer: what a serial port or a UDP feed delivers is split frames, junk,
// false magic bytes, corrupted bytes, frames of ids we do not decode and signed frames, so that
// is what these tests feed it.
#include <catch2/catch.hpp>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "helpers.hpp"

using namespace mavtest;

namespace {

// A framer with everything it delivered.
struct Harness {
    explicit Harness(FramerOptions options = {}) : framer(options) {}
    Framer framer;
    std::vector<Message> got;

    void push(std::span<const std::uint8_t> bytes) {
        framer.push(bytes, [&](const Message& m) { got.push_back(m); });
    }
    void push(const Bytes& bytes) { push(std::span<const std::uint8_t>(bytes)); }

    // Every byte pushed is in a delivered frame, a skipped frame, dropped, or waiting.
    bool counters_consistent() const {
        const FramerStats& s = framer.stats();
        return s.bytes ==
                   s.frame_bytes + s.skipped_bytes + s.dropped_bytes + framer.pending_bytes() &&
               s.frames == got.size();
    }
};

// A frame we can send and the message it must come out as.
struct Sample {
    Bytes wire;
    Message message;
};

// v1 and v2 frames of every message with random content, some with zero tails (truncated v2).
std::vector<Sample> sample_frames(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<Sample> out;
    for (std::size_t i = 0; i < 20; ++i) {
        const Payload p = random_payload(rng, i, i >= 10);
        const auto seq = static_cast<std::uint8_t>(rng());
        const auto sys = static_cast<std::uint8_t>(rng());
        const auto comp = static_cast<std::uint8_t>(rng());
        out.push_back(
            {encode_v1(p, sys, comp, seq), Message{1, seq, sys, comp, message_id(p), p, {}}});
        out.push_back(
            {encode_v2(p, sys, comp, seq), Message{2, seq, sys, comp, message_id(p), p, {}}});
    }
    return out;
}

std::vector<Message> messages_of(const std::vector<Sample>& samples) {
    std::vector<Message> out;
    for (const Sample& s : samples) out.push_back(s.message);
    return out;
}

// Clean frames to follow a false start: it can claim up to max_frame_size bytes and, with an
// unknown id, needs one byte more before it can be judged.
struct Tail {
    Bytes bytes;
    std::vector<Message> messages;
};
Tail clean_tail(const std::vector<Sample>& samples) {
    Tail tail;
    for (std::size_t i = 0; tail.bytes.size() <= max_frame_size; ++i) {
        const Sample& s = samples[i % samples.size()];
        tail.bytes.insert(tail.bytes.end(), s.wire.begin(), s.wire.end());
        tail.messages.push_back(s.message);
    }
    return tail;
}

// A frame of SYS_STATUS (1), which this codec does not decode (CRC_EXTRA 124).
Bytes unknown_v1() {
    return raw_v1(1, Bytes(31, 0x5A), 124);
}
// A MAVLink 2-only id (24-bit) with a truncated payload.
Bytes unknown_v2() {
    return raw_v2(0x012345, Bytes{1, 2, 3, 4, 5}, 77);
}

// Whether the bytes at `i` would be taken as a frame: the rule in framer.hpp, restated. Random
// junk that forms one is one, and would spoil the count.
bool frame_at(const Bytes& s, std::size_t i) {
    if (s[i] != magic_v1 && s[i] != magic_v2) return false;
    const bool v2 = s[i] == magic_v2;
    const std::size_t header = v2 ? header_size_v2 : header_size_v1;
    if (i + header > s.size()) return false;
    if (v2 && (s[i + 2] & ~incompat_signed) != 0) return false;
    const std::size_t len = s[i + 1];
    const std::uint32_t id =
        v2 ? static_cast<std::uint32_t>(s[i + 7] | (s[i + 8] << 8) | (s[i + 9] << 16)) : s[i + 5];
    const std::size_t total =
        header + len + checksum_size + ((v2 && (s[i + 2] & 1)) ? signature_size : 0);
    const MessageInfo* info = find_message(id);
    if (!info)
        return i + total < s.size() && (s[i + total] == magic_v1 || s[i + total] == magic_v2);
    if (!v2 && len < info->length) return false;
    if (i + total > s.size()) return false;
    const std::uint16_t crc = frame_crc(
        std::span<const std::uint8_t>(s).subspan(i + 1, header - 1 + len), info->crc_extra);
    return s[i + header + len] == (crc & 0xFF) && s[i + header + len + 1] == (crc >> 8);
}

}  // namespace

TEST_CASE("framer delivers every frame split at every byte offset", "[mavlink][framer]") {
    for (const Sample& sample : sample_frames(1)) {
        const Bytes& frame = sample.wire;
        for (std::size_t cut = 0; cut <= frame.size(); ++cut) {
            Harness h;
            h.push(std::span(frame).first(cut));
            CHECK(h.got.empty() == (cut < frame.size()));
            h.push(std::span(frame).subspan(cut));
            REQUIRE(h.got.size() == 1);
            CHECK(h.got[0] == sample.message);
            CHECK(h.framer.stats().dropped_bytes == 0);
            CHECK(h.framer.pending_bytes() == 0);
            CHECK(h.counters_consistent());
        }
    }
}

TEST_CASE("framer delivers a stream of frames split at every pair of offsets",
          "[mavlink][framer]") {
    const std::vector<Sample> samples = sample_frames(2);
    Bytes stream;
    for (const Sample& s : samples) stream.insert(stream.end(), s.wire.begin(), s.wire.end());
    const std::vector<Message> want = messages_of(samples);
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        const std::size_t cut2 = std::min(stream.size(), cut + 1 + cut % 90);
        Harness h;
        h.push(std::span(stream).first(cut));
        h.push(std::span(stream).subspan(cut, cut2 - cut));
        h.push(std::span(stream).subspan(cut2));
        REQUIRE(h.got == want);
        CHECK(h.framer.stats().dropped_bytes == 0);
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("framer delivers a frame pushed one byte at a time", "[mavlink][framer]") {
    Harness h;
    std::size_t delivered = 0;
    for (const Sample& s : sample_frames(3)) {
        for (std::size_t i = 0; i < s.wire.size(); ++i) {
            h.push(std::span(s.wire).subspan(i, 1));
            // Nothing comes out before the last byte, and the frame comes out on it.
            CHECK(h.got.size() == delivered + (i + 1 == s.wire.size() ? 1 : 0));
        }
        ++delivered;
        CHECK(h.got.back() == s.message);
        CHECK(h.framer.pending_bytes() == 0);
    }
    CHECK(h.framer.stats().dropped_bytes == 0);
    CHECK(h.counters_consistent());
}

TEST_CASE("framer finds every frame between random junk, in order", "[mavlink][framer][junk]") {
    const std::vector<Sample> samples = sample_frames(4);
    std::mt19937 rng(20240611);
    // Junk rich in magic bytes and the flag values a v2 header accepts, so that false starts
    // and cut-off headers happen often.
    auto junk_byte = [&]() -> std::uint8_t {
        switch (rng() % 6) {
            case 0:
                return magic_v1;
            case 1:
                return magic_v2;
            case 2:
                return static_cast<std::uint8_t>(rng() % 2);
            default:
                return static_cast<std::uint8_t>(rng());
        }
    };
    Bytes stream;
    std::vector<Message> want;
    std::vector<std::pair<std::size_t, std::size_t>> junk_ranges;
    std::uint64_t junk_total = 0;
    std::uint64_t unknown_total = 0;
    std::uint64_t unknown_bytes = 0;
    for (int n = 0; n < 3000; ++n) {
        const std::size_t junk_len = rng() % 24;
        junk_ranges.emplace_back(stream.size(), stream.size() + junk_len);
        for (std::size_t i = 0; i < junk_len; ++i) stream.push_back(junk_byte());
        junk_total += junk_len;
        if (n % 10 == 0) {  // a frame we do not decode, right before one we do
            const Bytes u = n % 20 == 0 ? unknown_v1() : unknown_v2();
            stream.insert(stream.end(), u.begin(), u.end());
            ++unknown_total;
            unknown_bytes += u.size();
        }
        const Sample& s = samples[rng() % samples.size()];
        stream.insert(stream.end(), s.wire.begin(), s.wire.end());
        want.push_back(s.message);
    }
    // A clean tail longer than any frame lets every false start resolve.
    while (stream.size() - junk_ranges.back().second < 2 * max_frame_size) {
        stream.insert(stream.end(), samples[0].wire.begin(), samples[0].wire.end());
        want.push_back(samples[0].message);
    }
    // Junk that happens to form a frame would be one: break its magic byte.
    for (bool clean = false; !clean;) {
        clean = true;
        for (const auto& [begin, end] : junk_ranges)
            for (std::size_t i = begin; i < end; ++i)
                if (frame_at(stream, i)) {
                    stream[i] = 0x00;
                    clean = false;
                }
    }

    // Push in random chunk sizes, some larger than two frames.
    Harness h;
    for (std::size_t at = 0; at < stream.size();) {
        const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 700);
        h.push(std::span(stream).subspan(at, n));
        at += n;
        REQUIRE(h.counters_consistent());
    }
    REQUIRE(h.got.size() == want.size());
    CHECK(h.got == want);
    const FramerStats& s = h.framer.stats();
    CHECK(s.dropped_bytes == junk_total);
    CHECK(s.unknown_ids == unknown_total);
    CHECK(s.skipped_bytes == unknown_bytes);
    CHECK(s.frames == want.size());
    CHECK(s.bad_crc > 0);  // the junk did contain false starts of each kind
    CHECK(s.bad_incompat > 0);
    CHECK(s.bad_length > 0);
    CHECK(h.framer.pending_bytes() == 0);
}

TEST_CASE("a stray magic byte before a frame costs one byte", "[mavlink][framer][false-magic]") {
    const std::vector<Sample> samples = sample_frames(5);
    const Sample& a = samples[4];  // ATTITUDE v1
    const Sample& b = samples[5];  // ATTITUDE v2
    const Tail tail = clean_tail(samples);
    for (const std::uint8_t stray : {magic_v1, magic_v2}) {
        CAPTURE(stray);
        {  // in the same push
            Harness h;
            h.push(concat({{stray}, a.wire, b.wire, tail.bytes}));
            REQUIRE(h.got.size() == 2 + tail.messages.size());
            CHECK(h.got[0] == a.message);
            CHECK(h.got[1] == b.message);
            CHECK(h.framer.stats().dropped_bytes == 1);
            CHECK(h.counters_consistent());
        }
        {  // alone at the end of a push
            Harness h;
            h.push(Bytes{0x55, stray});
            CHECK(h.framer.pending_bytes() == 1);  // might be the start of a frame
            h.push(concat({a.wire, b.wire, tail.bytes}));
            REQUIRE(h.got.size() == 2 + tail.messages.size());
            CHECK(h.got[0] == a.message);
            CHECK(h.framer.stats().dropped_bytes == 2);
            CHECK(h.counters_consistent());
        }
    }
    {  // FE FD FE FD before a v2 frame
        Harness h;
        h.push(concat({{magic_v1, magic_v2, magic_v1, magic_v2}, b.wire, tail.bytes}));
        REQUIRE(h.got.size() == 1 + tail.messages.size());
        CHECK(h.got[0] == b.message);
        CHECK(h.framer.stats().dropped_bytes == 4);
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("a false start waits only until it can be judged", "[mavlink][framer][false-magic]") {
    // A stray FE reads as a v1 header claiming 253 bytes: the frame behind it comes out once
    // those bytes (and, the id being unknown, one more) have arrived.
    const std::vector<Sample> samples = sample_frames(5);
    const Sample& v2 = samples[1];  // HEARTBEAT v2, starting FD
    Harness h;
    h.push(concat({{magic_v1}, v2.wire}));
    CHECK(h.got.empty());
    const std::size_t claimed = header_size_v1 + magic_v2 + checksum_size;
    const Tail tail = clean_tail(samples);
    std::size_t fed = 1 + v2.wire.size();
    for (std::size_t i = 0; h.got.empty(); ++i) {
        REQUIRE(i < tail.bytes.size());
        h.push(std::span(tail.bytes).subspan(i, 1));
        ++fed;
    }
    CHECK(fed <= claimed + 1);
    CHECK(h.got[0] == v2.message);
    CHECK(h.counters_consistent());
}

TEST_CASE("a false start claiming a long frame does not lose the frames inside it",
          "[mavlink][framer][false-magic]") {
    const std::vector<Sample> samples = sample_frames(6);
    const Tail tail = clean_tail(samples);
    for (const int length : {0, 1, 9, 28, 42, 100, 200, 255}) {
        const auto len = static_cast<std::uint8_t>(length);
        CAPTURE(len);
        // Known ids (CRC fails), an unknown id (no magic after it) and a signed v2 header.
        const std::vector<Bytes> false_headers{
            {magic_v1, len, 0, 1, 1, 30},
            {magic_v1, len, 0, 1, 1, 74},
            {magic_v2, len, 0, 0, 0, 1, 1, 33, 0, 0},
            {magic_v2, len, 1, 0, 0, 1, 1, 0, 0, 0},
            {magic_v2, len, 0, 0, 0, 1, 1, 0x45, 0x23, 0x01},
        };
        for (const Bytes& false_header : false_headers) {
            const Bytes stream =
                concat({false_header, samples[1].wire, samples[6].wire, tail.bytes});
            REQUIRE_FALSE(frame_at(stream, 0));
            for (const std::size_t chunk : {stream.size(), std::size_t{1}, std::size_t{7}}) {
                CAPTURE(false_header, chunk);
                Harness h;
                for (std::size_t at = 0; at < stream.size(); at += chunk)
                    h.push(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
                REQUIRE(h.got.size() == 2 + tail.messages.size());
                CHECK(h.got[0] == samples[1].message);
                CHECK(h.got[1] == samples[6].message);
                CHECK(h.framer.stats().dropped_bytes == false_header.size());
                CHECK(h.counters_consistent());
            }
        }
    }
}

TEST_CASE("a corrupted frame is counted and the next frame is delivered",
          "[mavlink][framer][crc]") {
    const std::vector<Sample> samples = sample_frames(7);
    const Tail tail = clean_tail(samples);
    const Sample& next = samples[2];
    for (const std::size_t which : {std::size_t{0}, std::size_t{1}, std::size_t{8},
                                    std::size_t{9}}) {  // HEARTBEAT, RC_CHANNELS; v1 and v2
        const Bytes& good = samples[which].wire;
        const bool v2 = good[0] == magic_v2;
        // Every byte after the magic is covered by the CRC (or is the CRC).
        for (std::size_t flip = 1; flip < good.size(); ++flip) {
            CAPTURE(which, flip);
            Bytes bad = good;
            bad[flip] ^= 0x04;
            Harness h;
            h.push(concat({bad, next.wire, tail.bytes}));
            REQUIRE(h.got.size() == 1 + tail.messages.size());
            CHECK(h.got[0] == next.message);
            const FramerStats& s = h.framer.stats();
            const bool in_msgid = v2 ? (flip >= 7 && flip <= 9) : flip == 5;
            const std::uint32_t id =
                v2 ? static_cast<std::uint32_t>(bad[7] | (bad[8] << 8) | (bad[9] << 16)) : bad[5];
            if (in_msgid && !find_message(id)) {
                // Now a frame of an id we do not know: nothing shows it is corrupt.
                CHECK(s.unknown_ids == 1);
                CHECK(s.skipped_bytes == bad.size());
            } else {
                CHECK(s.dropped_bytes == bad.size());
                CHECK(s.bad_crc + s.bad_length + s.bad_incompat >= 1);
            }
            CHECK(h.counters_consistent());
        }
    }
    SECTION("a payload byte flipped is a bad CRC, nothing else") {
        Bytes bad = samples[4].wire;
        bad[header_size_v1 + 3] ^= 0x80;
        Harness h;
        h.push(concat({bad, samples[2].wire, tail.bytes}));
        REQUIRE(h.got.size() == 1 + tail.messages.size());
        CHECK(h.framer.stats().bad_crc == 1);
        CHECK(h.framer.stats().dropped_bytes == bad.size());
    }
    SECTION("a frame checksummed with another CRC_EXTRA is rejected") {
        // A sender with another ATTITUDE definition.
        const Bytes other = raw_v2(Attitude::id, payload_of(Attitude{}), Attitude::crc_extra ^ 1);
        Harness h;
        h.push(concat({other, samples[2].wire, tail.bytes}));
        REQUIRE(h.got.size() == 1 + tail.messages.size());
        CHECK(h.framer.stats().bad_crc == 1);
    }
}

TEST_CASE("a v1 frame shorter than its message is a false start", "[mavlink][framer]") {
    const std::vector<Sample> samples = sample_frames(8);
    // A CRC-valid ATTITUDE v1 frame with 20 of its 28 bytes: not a frame we can trust.
    const Bytes short_frame = raw_v1(Attitude::id, Bytes(20, 0x01), Attitude::crc_extra);
    Harness h;
    h.push(concat({short_frame, samples[0].wire}));
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == samples[0].message);
    CHECK(h.framer.stats().bad_length == 1);
    CHECK(h.framer.stats().dropped_bytes == short_frame.size());
    CHECK(h.counters_consistent());
}

TEST_CASE("a v2 frame with an unknown incompat flag is rejected", "[mavlink][framer][incompat]") {
    const std::vector<Sample> samples = sample_frames(9);
    const Bytes payload = payload_of(Heartbeat{0, 2, 3, 0x51, 4, 3});
    for (const int flag_bits : {0x02, 0x04, 0x80, 0x03, 0xFF}) {
        const auto flags = static_cast<std::uint8_t>(flag_bits);
        CAPTURE(flags);
        // CRC-valid, so only the flag can be the reason.
        const Bytes frame = raw_v2(Heartbeat::id, payload, Heartbeat::crc_extra, flags);
        Harness h;
        h.push(concat({frame, samples[1].wire}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == samples[1].message);
        CHECK(h.framer.stats().bad_incompat == 1);
        CHECK(h.framer.stats().dropped_bytes == frame.size());
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("signed frames are rejected by default and accepted when configured",
          "[mavlink][framer][signing]") {
    const std::vector<Sample> samples = sample_frames(10);
    // The Pixhawk HEARTBEAT with incompat flag 0x01 and a 13-byte signature after the CRC
    // (CRC 0x7194, computed by hand over the header with the flag set).
    const Bytes signed_frame =
        concat({{0xFD, 0x09, 0x01, 0x00, 0xEF, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00,
                 0x00, 0x00, 0x00, 0x02, 0x03, 0x51, 0x03, 0x03, 0x94, 0x71},
                fake_signature()});
    CHECK(signed_frame == raw_v2(Heartbeat::id, payload_of(Heartbeat{0, 2, 3, 0x51, 3, 3}),
                                 Heartbeat::crc_extra, incompat_signed, fake_signature(), 0xEF));
    const Sample& next = samples[3];
    SECTION("default: skipped whole and counted") {
        Harness h;
        h.push(concat({signed_frame, next.wire}));
        REQUIRE(h.got.size() == 1);
        CHECK(h.got[0] == next.message);
        const FramerStats& s = h.framer.stats();
        CHECK(s.signed_rejected == 1);
        CHECK(s.skipped_bytes == signed_frame.size());
        CHECK(s.dropped_bytes == 0);
        CHECK(h.counters_consistent());
    }
    SECTION("accept_signed: delivered with its signature fields, not verified without a key") {
        for (std::size_t cut = 0; cut <= signed_frame.size(); ++cut) {
            CAPTURE(cut);
            Harness h(FramerOptions{.accept_signed = true, .signing_key = {}});
            const Bytes stream = concat({signed_frame, next.wire});
            h.push(std::span(stream).first(cut));
            h.push(std::span(stream).subspan(cut));
            REQUIRE(h.got.size() == 2);
            CHECK(h.got[0] == Message{2, 0xEF, 1, 1, 0, Heartbeat{0, 2, 3, 0x51, 3, 3},
                                      Signature{0x01, 0x605040302010, false}});
            CHECK(h.got[1] == next.message);
            const FramerStats& s = h.framer.stats();
            CHECK(s.signed_rejected == 0);
            CHECK(s.frame_bytes == stream.size());
            CHECK(s.dropped_bytes == 0);
            CHECK(h.counters_consistent());
        }
    }
    SECTION("a signed frame with a bad CRC is a false start either way") {
        Bytes bad = signed_frame;
        bad[12] ^= 0x01;
        const Tail tail = clean_tail(samples);
        for (const bool accept : {false, true}) {
            Harness h(FramerOptions{.accept_signed = accept, .signing_key = {}});
            h.push(concat({bad, next.wire, tail.bytes}));
            REQUIRE(h.got.size() == 1 + tail.messages.size());
            CHECK(h.got[0] == next.message);
            // The signature's FE FD are false starts of their own.
            CHECK(h.framer.stats().bad_crc >= 1);
            CHECK(h.framer.stats().signed_rejected == 0);
            CHECK(h.framer.stats().dropped_bytes == bad.size());
        }
    }
}

TEST_CASE("frames of unknown ids are skipped and counted", "[mavlink][framer][unknown]") {
    const std::vector<Sample> samples = sample_frames(11);
    const Sample& next = samples[5];
    const Bytes signed_unknown = raw_v2(0x2222, Bytes(10, 7), 1, incompat_signed, fake_signature());
    for (const Bytes& unknown : {unknown_v1(), unknown_v2(), signed_unknown}) {
        for (std::size_t cut = 0; cut <= unknown.size() + 1; ++cut) {
            CAPTURE(unknown.size(), cut);
            const Bytes stream = concat({unknown, unknown, next.wire});
            Harness h;
            h.push(std::span(stream).first(cut));
            h.push(std::span(stream).subspan(cut));
            REQUIRE(h.got.size() == 1);
            CHECK(h.got[0] == next.message);
            const FramerStats& s = h.framer.stats();
            CHECK(s.unknown_ids == 2);
            CHECK(s.skipped_bytes == 2 * unknown.size());
            CHECK(s.dropped_bytes == 0);
            CHECK(h.counters_consistent());
        }
    }
    SECTION("an unknown frame is skipped once the next frame's first byte has arrived") {
        Harness h;
        h.push(unknown_v2());
        CHECK(h.framer.stats().unknown_ids == 0);
        CHECK(h.framer.pending_bytes() == unknown_v2().size());
        h.push(std::span(next.wire).first(1));
        CHECK(h.framer.stats().unknown_ids == 1);
        CHECK(h.framer.pending_bytes() == 1);
    }
    SECTION("an unknown frame followed by junk is not trusted") {
        // Its length cannot be checked, so its bytes are scanned for frames.
        const Bytes unknown = raw_v1(74, concat({Bytes{0x00}, next.wire, Bytes(3, 0)}), 20);
        Harness h;
        h.push(concat({unknown, Bytes{0x00}, samples[0].wire}));
        REQUIRE(h.got.size() == 2);
        CHECK(h.got[0] == next.message);  // the frame inside the "unknown" one
        CHECK(h.got[1] == samples[0].message);
        CHECK(h.framer.stats().unknown_ids == 0);
        CHECK(h.counters_consistent());
    }
}

TEST_CASE("reset() forgets a partial frame", "[mavlink][framer]") {
    const Sample s = sample_frames(12)[3];
    const std::size_t half = s.wire.size() / 2;
    Harness h;
    h.push(std::span(s.wire).first(half));
    CHECK(h.framer.pending_bytes() == half);
    h.framer.reset();
    CHECK(h.framer.pending_bytes() == 0);
    CHECK(h.framer.stats().dropped_bytes == half);
    CHECK(h.counters_consistent());
    // The rest of the old frame is now junk; the next whole frame still comes through.
    h.push(std::span(s.wire).subspan(half));
    h.push(s.wire);
    REQUIRE(h.got.size() == 1);
    CHECK(h.got[0] == s.message);
    CHECK(h.counters_consistent());
}

TEST_CASE("the vector form of push() returns the same messages", "[mavlink][framer]") {
    const std::vector<Sample> samples = sample_frames(13);
    Bytes stream;
    for (const Sample& s : samples) stream.insert(stream.end(), s.wire.begin(), s.wire.end());
    Framer framer;
    CHECK(framer.push(stream) == messages_of(samples));
    CHECK(framer.stats().frames == samples.size());
    CHECK(framer.stats().bytes == stream.size());
}

TEST_CASE("datagrams are parsed one by one: garbage of any shape cannot hold the next one",
          "[mavlink][framer][datagram]") {
    const std::vector<Sample> samples = sample_frames(14);
    const Sample& good = samples[7];
    const Sample& other = samples[2];
    // A plausible header of an unknown id claiming the longest frame MAVLink has (280 bytes
    // with a signature), a v1 one, and one of a known id whose length reaches past the end.
    const Bytes long_unknown_v2 = {0xFD, 0xFF, 0x01, 0x00, 0x07, 0x01, 0x01, 0x39, 0x30, 0x00};
    const Bytes long_unknown_v1 = {0xFE, 0xFF, 0x07, 0x01, 0x01, 0xC8, 0x11, 0x22};
    const Bytes known_truncated = {0xFD, 0x21, 0x00, 0x00, 0x07, 0xFF, 0xBE, 0x4C, 0x00, 0x00};
    Bytes bad_crc = good.wire;
    bad_crc.back() ^= 0xFF;
    Bytes random_junk(300);
    std::mt19937 rng(99);
    for (auto& b : random_junk) b = static_cast<std::uint8_t>(rng());
    random_junk[17] = 0xFD;  // with plausible headers inside
    random_junk[18] = 0x80;
    random_junk[19] = 0x01;
    const std::vector<std::pair<const char*, Bytes>> garbage = {
        {"truncated header", {0xFD, 0x20, 0x00}},
        {"lone magic", {0xFE}},
        {"unknown id, length 255, signed flag", long_unknown_v2},
        {"unknown id, v1, length 255", long_unknown_v1},
        {"known id, length past the end", known_truncated},
        {"signed-flag garbage", {0xFD, 0x40, 0x01, 0x00, 0x00, 0x01, 0x01, 0x77, 0x77, 0x07, 0x01}},
        {"valid frame + junk", concat({other.wire, long_unknown_v2})},
        {"junk + valid frame", concat({Bytes{0x01, 0xFD, 0x05}, other.wire})},
        {"bad CRC", bad_crc},
        {"random bytes", random_junk},
    };
    for (const auto& [what, bytes] : garbage) {
        CAPTURE(what);
        Harness h;
        h.framer.push_datagram(bytes, [&](const Message& m) { h.got.push_back(m); });
        CHECK(h.framer.pending_bytes() == 0);
        const std::size_t before = h.got.size();
        h.framer.push_datagram(good.wire, [&](const Message& m) { h.got.push_back(m); });
        REQUIRE(h.got.size() == before + 1);  // the next datagram's frame, at once
        CHECK(h.got.back() == good.message);
        CHECK(h.counters_consistent());
    }
    SECTION("the same garbage as a stream holds the next frame back (serial stays a stream)") {
        Harness h;
        h.push(long_unknown_v2);
        h.push(good.wire);
        CHECK(h.got.empty());
    }
    SECTION("frames inside a datagram: all delivered; an unknown frame ending it is skipped") {
        Harness h;
        const Bytes datagram = concat({other.wire, good.wire, unknown_v2()});
        CHECK(h.framer.push_datagram(datagram) ==
              std::vector<Message>{other.message, good.message});
        CHECK(h.framer.stats().unknown_ids == 1);
        CHECK(h.framer.stats().dropped_bytes == 0);
    }
}
