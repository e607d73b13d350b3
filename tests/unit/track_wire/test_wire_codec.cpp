// The gimbald <-> gimbal-track messages: byte layout pinned by hand-written datagrams (the
// layout docs/tracking.md documents), round trips of every message, and every way a hostile
// or broken datagram is refused.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "track/wire/codec.hpp"

using namespace gimbal::track::wire;
using Bytes = std::vector<std::uint8_t>;

namespace {

template <class M>
M round_trip(const M& m) {
    const Bytes bytes = encode(m);
    REQUIRE_FALSE(bytes.empty());
    const auto decoded = decode(bytes);
    INFO(decoded.error);
    REQUIRE(decoded.message);
    REQUIRE(std::holds_alternative<M>(*decoded.message));
    return std::get<M>(*decoded.message);
}

std::string refusal(const Bytes& bytes) {
    const auto decoded = decode(bytes);
    CHECK_FALSE(decoded.message);
    return decoded.error;
}

Bytes box_datagram() {
    return {1,    5,                                // version, type box
            7,    0,    0,    0,                    // id 7
            0x05, 0x04, 0x03, 0x02, 0x01, 0, 0, 0,  // pts_90k 0x0102030405
            0,    0,    0,    0xBF,                 // x0 -0.5
            0,    0,    0x80, 0xBE,                 // y0 -0.25
            0,    0,    0,    0x3F,                 // x1 0.5
            0,    0,    0x80, 0x3E,                 // y1 0.25
            0,    0,    0x40, 0x3F,                 // confidence 0.75
            1};                                     // state lost
}

}  // namespace

TEST_CASE("wire: a box is laid out as documented", "[track][wire]") {
    Box b;
    b.id = 7;
    b.pts_90k = 0x0102030405;
    b.x0 = -0.5f;
    b.y0 = -0.25f;
    b.x1 = 0.5f;
    b.y1 = 0.25f;
    b.confidence = 0.75f;
    b.state = BoxState::lost;
    CHECK(encode(b) == box_datagram());
    const auto back = decode(box_datagram());
    REQUIRE(back.message);
    const auto& d = std::get<Box>(*back.message);
    CHECK(d.id == 7);
    CHECK(d.pts_90k == 0x0102030405);
    CHECK(d.x0 == -0.5f);
    CHECK(d.y1 == 0.25f);
    CHECK(d.confidence == 0.75f);
    CHECK(d.state == BoxState::lost);
}

TEST_CASE("wire: an access unit carries its bytes after a length", "[track][wire]") {
    const Bytes payload{0, 0, 0, 1, 0x65, 0x88};
    AccessUnit au;
    au.pts_90k = -3;  // negative times pass: the clock, not the codec, judges them
    au.key = true;
    au.codec = Codec::h265;
    au.bytes = payload;
    au.total_bytes = 6;
    const Bytes expected{1,    3,                                         // au
                         0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,  // pts -3
                         1,                                               // key
                         1,                                               // h265
                         6,    0,    0,    0,                             // total_bytes
                         0,    0,    0,    0,                             // offset
                         6,    0,    0,    0,                             // length
                         0,    0,    0,    1,    0x65, 0x88};
    const Bytes bytes = encode(au);
    CHECK(bytes == expected);
    const auto decoded = decode(bytes);
    REQUIRE(decoded.message);
    const auto& back = std::get<AccessUnit>(*decoded.message);
    CHECK(back.pts_90k == -3);
    CHECK(back.key);
    CHECK(back.codec == Codec::h265);
    CHECK(Bytes(back.bytes.begin(), back.bytes.end()) == payload);
    CHECK(back.total_bytes == 6);
    CHECK(back.offset == 0);
    CHECK(back.bytes.data() == bytes.data() + 24);  // a view, not a copy
}

TEST_CASE("wire: every message survives a round trip", "[track][wire]") {
    Hello h;
    h.trackers = {"csrt", "kcf"};
    const auto hb = round_trip(h);
    CHECK(hb.version == protocol_version);
    CHECK(hb.trackers == h.trackers);
    CHECK(hb.max_au_bytes == max_access_unit_bytes);

    Start s;
    s.id = 42;
    s.x0 = -0.1f;
    s.y0 = -0.2f;
    s.x1 = 0.1f;
    s.y1 = 0.2f;
    s.tracker = TrackerKind::csrt;
    s.width = 1280;
    s.lost_after_s = 0.5f;
    s.reacquire_s = 3;
    const auto sb = round_trip(s);
    CHECK(sb.id == 42);
    CHECK(sb.x0 == -0.1f);
    CHECK(sb.y1 == 0.2f);
    CHECK(sb.tracker == TrackerKind::csrt);
    CHECK(sb.width == 1280);
    CHECK(sb.lost_after_s == 0.5f);
    CHECK(sb.reacquire_s == 3.0f);

    CHECK(round_trip(Stop{.id = 9}).id == 9);
    const auto e = round_trip(Ended{.id = 3, .reason = EndReason::no_video});
    CHECK(e.id == 3);
    CHECK(e.reason == EndReason::no_video);
    CHECK(round_trip(Error{.message = "decoder: bad NAL"}).message == "decoder: bad NAL");
    CHECK(round_trip(Error{.message = ""}).message.empty());
}

TEST_CASE("wire: header problems are refused", "[track][wire]") {
    CHECK(refusal({}) == "shorter than the header");
    CHECK(refusal({1}) == "shorter than the header");
    CHECK(refusal({2, 5}) == "protocol version 2, expected 1");
    CHECK(refusal({1, 0}) == "unknown message type 0");
    CHECK(refusal({1, 8}) == "unknown message type 8");
    CHECK_FALSE(peek_type(Bytes{1, 8}));
    CHECK(peek_type(box_datagram()) == MessageType::box);
}

TEST_CASE("wire: a datagram cut anywhere is refused", "[track][wire]") {
    const Bytes whole = box_datagram();
    for (std::size_t n = 2; n < whole.size(); ++n) {
        INFO(n);
        const auto error = refusal(Bytes(whole.begin(), whole.begin() + static_cast<long>(n)));
        CHECK(error.find("cut short") != std::string::npos);
    }
    Bytes longer = whole;
    longer.push_back(0);
    CHECK(refusal(longer) == "box: bytes after the message");
}

TEST_CASE("wire: values outside their declaration are refused", "[track][wire]") {
    auto with = [](std::size_t at, std::initializer_list<std::uint8_t> bytes) {
        Bytes b = box_datagram();
        std::copy(bytes.begin(), bytes.end(), b.begin() + static_cast<long>(at));
        return b;
    };
    CHECK(refusal(with(14, {0, 0, 0xC0, 0x7F})) == "box.x0: not a finite number");   // NaN
    CHECK(refusal(with(14, {0, 0, 0x80, 0x7F})) == "box.x0: not a finite number");   // +inf
    CHECK(refusal(with(14, {0, 0, 0xA0, 0x40})) == "box.x0: out of range");          // 5.0
    CHECK(refusal(with(30, {0, 0, 0xC0, 0x3F})) == "box.confidence: out of range");  // 1.5
    CHECK(refusal(with(34, {2})) == "box.state: not one of its values");

    // pts 0, key, codec, total_bytes, offset, length
    Bytes au{1, 3, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK(refusal(au) == "au.key: not 0 or 1");
    au[10] = 1;
    au[11] = 2;
    CHECK(refusal(au) == "au.codec: not one of its values");
    au[11] = 0;
    CHECK(decode(au).message);  // an empty access unit is well-formed
    auto put32 = [&](std::size_t at, std::uint32_t v) {
        for (std::size_t i = 0; i < 4; ++i) au[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
    };
    const auto too_long = static_cast<std::uint32_t>(max_access_unit_bytes + 1);
    put32(12, too_long);
    CHECK(refusal(au) == "au.total_bytes: out of range");
    put32(12, 10);
    put32(16, 11);
    CHECK(refusal(au) == "au: offset + piece beyond total_bytes");
    put32(16, 0);
    put32(20, too_long);  // a length beyond the cap is refused before anything is read
    CHECK(refusal(au) == "au.bytes: too long");
    put32(20, 1u << 20);  // 1 MiB claimed, none there
    CHECK(refusal(au) == "au.bytes: cut short");
    put32(20, 0);
    CHECK(decode(au).message);

    Start s;
    s.x0 = 0.5f;
    s.x1 = 0.5f;
    std::string error;
    Bytes out{9};
    CHECK_FALSE(encode(Message{s}, out, &error));
    CHECK(out.empty());
    CHECK(error == "start: box: x1 must exceed x0 and y1 exceed y0");
    s.x1 = 0.6f;
    s.width = 20;
    CHECK_FALSE(encode(Message{s}, out, &error));
    CHECK(error == "start.width: out of range");
    s.width = 640;
    s.reacquire_s = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(encode(Message{s}, out, &error));
    CHECK(error == "start.reacquire_s: not a finite number");

    Error long_text{std::string(max_text_bytes + 1, 'x')};
    CHECK_FALSE(encode(Message{long_text}, out, &error));
    CHECK(error == "error.message: too long");
    Bytes text{1, 7, 0xE9, 0x03};  // length 1001
    text.resize(text.size() + 1001, 'x');
    CHECK(refusal(text) == "error.message: too long");

    Hello many;
    many.trackers.assign(max_list_items + 1, "kcf");
    CHECK_FALSE(encode(Message{many}, out, &error));
    CHECK(error == "hello.trackers: too many items");
}

TEST_CASE("wire: an oversized datagram is refused whole", "[track][wire]") {
    Bytes huge(max_datagram_bytes + 1, 0);
    huge[0] = 1;
    huge[1] = 3;
    CHECK(refusal(huge) == "larger than a datagram may be");
}
