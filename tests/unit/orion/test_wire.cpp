// Wire encodings (wire.hpp) and the encoder/decoder (codec.hpp) against hand-computed bytes.
// The probe packets below are test-only declarations: the codec only needs fields().
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "protocols/orion/codec/codec.hpp"
#include "protocols/orion/codec/wire.hpp"

using namespace gimbal::orion;
using Bytes = std::vector<std::uint8_t>;

namespace {

Bytes bytes_of(const Payload& p) {
    return Bytes(p.bytes.begin(), p.bytes.begin() + p.size);
}

std::uint16_t f16(double v) {
    return static_cast<std::uint16_t>(float_to_small(v, 16, 9));
}
double from_f16(std::uint32_t raw) {
    return small_to_float(raw, 16, 9);
}

// One scalar of type T in encoding E with scale s, through the encoder and decoder visitors.
template <class T, class E>
Bytes encode_one(T value, E enc, Scale s = {}) {
    Payload out;
    Encoder encoder(out);
    encoder.field("value", value, enc, s);
    REQUIRE(encoder.ok());
    return bytes_of(out);
}

template <class T, class E>
T decode_one(const Bytes& data, E enc, Scale s = {}) {
    Decoder decoder(data);
    T value{};
    decoder.field("value", value, enc, s);
    REQUIRE(decoder.ok());
    return value;
}

}  // namespace

// --- F16:9 -------------------------------------------------------------------------------
// 1 sign bit, 6 exponent bits (bias 31), 9 significand bits with an implied leading one.

TEST_CASE("F16:9 encodes hand-computed vectors", "[orion][wire][f16]") {
    CHECK(f16(1.0) == 0x3E00);   // exponent 0 -> 31 << 9
    CHECK(f16(-2.5) == 0xC080);  // sign, exponent 1 -> 32 << 9, significand .25 * 512 = 128
    CHECK(f16(0.0) == 0x0000);
    CHECK(f16(-0.0) == 0x8000);
    CHECK(f16(0.5) == 0x3C00);    // exponent -1 -> 30 << 9
    CHECK(f16(3.0) == 0x4100);    // 1.5 * 2^1
    CHECK(f16(100.0) == 0x4B20);  // 1.5625 * 2^6: (37 << 9) | 288
}

TEST_CASE("F16:9 decodes hand-computed vectors", "[orion][wire][f16]") {
    CHECK(from_f16(0x3E00) == 1.0);
    CHECK(from_f16(0xC080) == -2.5);
    CHECK(from_f16(0x4B20) == 100.0);
    CHECK(from_f16(0x0000) == 0.0);
    CHECK(std::signbit(from_f16(0x8000)));
    CHECK(from_f16(0x8000) == 0.0);
}

TEST_CASE("F16:9 rounds the significand half away from zero", "[orion][wire][f16]") {
    // 1 + 2^-10 is exactly half of one significand step above 1.0.
    CHECK(f16(1.0 + std::ldexp(1.0, -10)) == 0x3E01);
    CHECK(f16(-(1.0 + std::ldexp(1.0, -10))) == 0xBE01);
    CHECK(f16(1.0 + std::ldexp(1.0, -11)) == 0x3E00);  // a quarter step: down
    // 33.34 is 1.041875 * 2^5: .041875 * 512 = 21.44 -> 21
    CHECK(f16(33.34) == ((36u << 9) | 21u));
    CHECK(from_f16(f16(33.34)) == Approx(33.34).epsilon(1.0 / 512));
    // ProtoGen never lets the rounding carry into the exponent: just below 2.0 stays below.
    CHECK(f16(2.0 - std::ldexp(1.0, -12)) == 0x3FFF);
    CHECK(from_f16(0x3FFF) == 2.0 - std::ldexp(1.0, -9));
}

TEST_CASE("F16:9 saturates at the largest finite value", "[orion][wire][f16]") {
    const double largest = (1.0 + 511.0 / 512.0) * std::ldexp(1.0, 31);  // 4290772992
    CHECK(from_f16(0x7DFF) == largest);
    CHECK(f16(largest) == 0x7DFF);
    CHECK(f16(1e12) == 0x7DFF);
    CHECK(f16(-1e12) == 0xFDFF);
    CHECK(f16(std::numeric_limits<double>::infinity()) == 0x7DFF);
    CHECK(f16(-std::numeric_limits<double>::infinity()) == 0xFDFF);
    CHECK(f16(std::numeric_limits<double>::quiet_NaN()) == 0x0000);
}

TEST_CASE("F16:9 underflows to a signed zero and has no denormals", "[orion][wire][f16]") {
    // The smallest exponent, -31, is biased to 0 and still has an implied leading one.
    CHECK(f16(1.5 * std::ldexp(1.0, -31)) == 0x0100);
    CHECK(from_f16(0x0100) == 1.5 * std::ldexp(1.0, -31));
    CHECK(from_f16(0x0001) == (1.0 + 1.0 / 512) * std::ldexp(1.0, -31));
    // Below that: zero, keeping the sign.
    CHECK(f16(std::ldexp(1.0, -32)) == 0x0000);
    CHECK(f16(-std::ldexp(1.0, -40)) == 0x8000);
    CHECK(f16(1e-45) == 0x0000);  // a float32 denormal
    // The all-ones exponent is an ordinary (finite) number too.
    CHECK(from_f16(0x7E00) == std::ldexp(1.0, 32));
}

TEST_CASE("an F16:9 field round-trips through the codec", "[orion][wire][f16]") {
    CHECK(encode_one(-2.5, f16_9) == Bytes{0xC0, 0x80});
    CHECK(decode_one<double>(Bytes{0x4B, 0x20}, f16_9) == 100.0);
    CHECK(decode_one<float>(Bytes{0x3E, 0x00}, f16_9) == 1.0f);
}

// --- scaled integers ---------------------------------------------------------------------

TEST_CASE("scaled integers round half away from zero", "[orion][wire][round]") {
    CHECK(encode_one(2.5, i16) == Bytes{0x00, 0x03});
    CHECK(encode_one(-2.5, i16) == Bytes{0xFF, 0xFD});
    CHECK(encode_one(2.4999, i16) == Bytes{0x00, 0x02});
    CHECK(encode_one(-0.5, i16) == Bytes{0xFF, 0xFF});
    CHECK(encode_one(0.5, u8) == Bytes{0x01});
    CHECK(encode_one(-0.4, i8) == Bytes{0x00});
    // With a scale: 0.0125 * 100 = 1.25 -> 1, 0.025 * 100 = 2.5 -> 3
    CHECK(encode_one(0.0125, i16, 100.0) == Bytes{0x00, 0x01});
    CHECK(encode_one(0.025, i16, 100.0) == Bytes{0x00, 0x03});  // 2.5 -> 3
    CHECK(encode_one(-0.025, i16, 100.0) == Bytes{0xFF, 0xFD});
}

TEST_CASE("signed fields saturate symmetrically, unsigned at 0 and all ones",
          "[orion][wire][saturate]") {
    CHECK(encode_one(40000.0, i16) == Bytes{0x7F, 0xFF});
    CHECK(encode_one(-40000.0, i16) == Bytes{0x80, 0x01});  // -32767, never -32768
    CHECK(encode_one(-32767.6, i16) == Bytes{0x80, 0x01});
    CHECK(encode_one(-200.0, i8) == Bytes{0x81});
    CHECK(encode_one(1e10, i32) == Bytes{0x7F, 0xFF, 0xFF, 0xFF});
    CHECK(encode_one(-1e10, i32) == Bytes{0x80, 0x00, 0x00, 0x01});
    CHECK(encode_one(-5.0, u16) == Bytes{0x00, 0x00});
    CHECK(encode_one(70000.0, u16) == Bytes{0xFF, 0xFF});
    CHECK(encode_one(300.0, u8) == Bytes{0xFF});
    CHECK(encode_one(std::numeric_limits<double>::quiet_NaN(), i16) == Bytes{0x00, 0x00});
    CHECK(encode_one(std::numeric_limits<double>::infinity(), u8) == Bytes{0xFF});
    // Integer members take the exact path and saturate the same way.
    CHECK(encode_one(std::int32_t{-40000}, i16) == Bytes{0x80, 0x01});
    CHECK(encode_one(std::int32_t{40000}, i16) == Bytes{0x7F, 0xFF});
    CHECK(encode_one(std::uint32_t{70000}, u16) == Bytes{0xFF, 0xFF});
    CHECK(encode_one(std::int32_t{-1}, u16) == Bytes{0x00, 0x00});
    CHECK(encode_one(std::uint32_t{70000}, i16) == Bytes{0x7F, 0xFF});
}

TEST_CASE("8-byte fields saturate without overflowing", "[orion][wire][saturate]") {
    CHECK(encode_one(1e30, i64) == Bytes{0x7F, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
    CHECK(encode_one(-1e30, i64) == Bytes{0x80, 0, 0, 0, 0, 0, 0, 0x01});
    CHECK(encode_one(1e30, u64) == Bytes(8, 0xFF));
    CHECK(encode_one(std::numeric_limits<std::int64_t>::min(), i64) ==
          Bytes{0x80, 0, 0, 0, 0, 0, 0, 0x01});
    CHECK(encode_one(std::numeric_limits<std::uint64_t>::max(), u64) == Bytes(8, 0xFF));
    CHECK(encode_one(-1234567.0, i64) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xED, 0x29, 0x79});
}

TEST_CASE("the decoder accepts the one value the encoder never sends", "[orion][wire]") {
    // 0x8000 is -32768: lenient decode keeps it although the encoder saturates at -32767.
    CHECK(decode_one<double>(Bytes{0x80, 0x00}, i16) == -32768.0);
    CHECK(decode_one<std::int16_t>(Bytes{0x80, 0x00}, i16) == -32768);
}

TEST_CASE("U24 and I24 carry their sign correctly", "[orion][wire][int24]") {
    CHECK(encode_one(-1.0, i24) == Bytes{0xFF, 0xFF, 0xFF});
    CHECK(encode_one(8388607.0, i24) == Bytes{0x7F, 0xFF, 0xFF});
    CHECK(encode_one(-9e6, i24) == Bytes{0x80, 0x00, 0x01});
    CHECK(encode_one(70000.0, u24) == Bytes{0x01, 0x11, 0x70});
    CHECK(encode_one(2e7, u24) == Bytes{0xFF, 0xFF, 0xFF});
    CHECK(encode_one(std::int32_t{-70000}, i24) == Bytes{0xFE, 0xEE, 0x90});
    CHECK(decode_one<double>(Bytes{0xFF, 0xFF, 0xFF}, i24) == -1.0);
    CHECK(decode_one<double>(Bytes{0xFF, 0xFF, 0xFF}, u24) == 16777215.0);
    CHECK(decode_one<std::int32_t>(Bytes{0x80, 0x00, 0x00}, i24) == -8388608);
    CHECK(decode_one<std::int32_t>(Bytes{0xFE, 0xEE, 0x90}, i24) == -70000);
    CHECK(decode_one<std::uint32_t>(Bytes{0x80, 0x00, 0x00}, u24) == 0x800000u);
}

TEST_CASE("a scale with an offset maps the range start to zero", "[orion][wire][scale]") {
    // "Scaled by 255/29.0 from 1.0 to 30.0": raw = round((v - 1) * 255 / 29)
    const Scale s{255.0 / 29.0, 1.0};
    CHECK(encode_one(1.0, u8, s) == Bytes{0x00});
    CHECK(encode_one(30.0, u8, s) == Bytes{0xFF});
    CHECK(encode_one(15.6, u8, s) == Bytes{0x80});  // 128.38 -> 128
    CHECK(encode_one(2.0, u8, s) == Bytes{0x09});   // 8.79 -> 9
    CHECK(encode_one(0.0, u8, s) == Bytes{0x00});   // below the range: saturates
    CHECK(encode_one(31.0, u8, s) == Bytes{0xFF});
    CHECK(decode_one<double>(Bytes{0x80}, u8, s) == Approx(128.0 * 29.0 / 255.0 + 1.0));
    CHECK(decode_one<double>(Bytes{0x00}, u8, s) == 1.0);
    // With a negative offset and a signed field
    const Scale t{10.0, -5.0};
    CHECK(encode_one(-5.0, i8, t) == Bytes{0x00});
    CHECK(encode_one(0.0, i8, t) == Bytes{0x32});
    CHECK(decode_one<double>(Bytes{0xCE}, i8, t) == Approx(-10.0));
}

TEST_CASE("IEEE floats are big-endian", "[orion][wire][float]") {
    CHECK(encode_one(1.0, f32) == Bytes{0x3F, 0x80, 0x00, 0x00});
    CHECK(encode_one(-2.5, f64) == Bytes{0xC0, 0x04, 0, 0, 0, 0, 0, 0});
    CHECK(decode_one<double>(Bytes{0xC0, 0x20, 0x00, 0x00}, f32) == -2.5);
}

TEST_CASE("integer members decoded from float fields saturate instead of overflowing",
          "[orion][wire][saturate]") {
    CHECK(decode_one<std::uint8_t>(Bytes{0x4F, 0x80, 0x00, 0x00}, f32) == 255);  // 4.29e9
    CHECK(decode_one<std::int16_t>(Bytes{0xCF, 0x80, 0x00, 0x00}, f32) == -32768);
    CHECK(decode_one<std::int32_t>(Bytes{0x7F, 0xC0, 0x00, 0x00}, f32) == 0);   // NaN
    CHECK(decode_one<std::uint32_t>(Bytes{0xBF, 0x80, 0x00, 0x00}, f32) == 0);  // -1
}

// --- bitfields ---------------------------------------------------------------------------

namespace {

// B3, B7, B6 across two bytes, then a whole U8.
struct CrossingBits {
    std::uint8_t a = 0;
    std::uint8_t b = 0;
    std::uint8_t c = 0;
    std::uint8_t tail = 0;
    template <class V>
    void fields(V& v) {
        v.bits("a", a, 3);
        v.bits("b", b, 7);
        v.bits("c", c, 6);
        v.field("tail", tail, u8);
    }
};

// A bit group that does not fill its byte, then whole-byte fields.
struct PartialBits {
    bool flag = false;
    std::uint8_t code = 0;
    std::uint16_t after = 0;
    template <class V>
    void fields(V& v) {
        v.bits("flag", flag, 1);
        v.bits("code", code, 2);
        v.field("after", after, u16);
    }
};

// B4 reserved, B12, B8 spanning three bytes.
struct WideBits {
    std::uint16_t twelve = 0;
    std::uint8_t eight = 0;
    template <class V>
    void fields(V& v) {
        v.reserved_bits(4);
        v.bits("twelve", twelve, 12);
        v.bits("eight", eight, 8);
    }
};

}  // namespace

TEST_CASE("bitfields pack MSB first across byte boundaries", "[orion][wire][bits]") {
    // a=101 b=1100110 c=011011: 1011 1001 | 1001 1011 -> B9 9B
    CrossingBits p{0b101, 0b1100110, 0b011011, 0x42};
    const Payload out = encode(p);
    CHECK(bytes_of(out) == Bytes{0xB9, 0x9B, 0x42});
    auto back = decode<CrossingBits>(out.view());
    REQUIRE(back.ok);
    CHECK(back.value.a == 0b101);
    CHECK(back.value.b == 0b1100110);
    CHECK(back.value.c == 0b011011);
    CHECK(back.value.tail == 0x42);
}

TEST_CASE("a field after a partly filled bitfield byte starts on the next byte",
          "[orion][wire][bits]") {
    PartialBits p{true, 2, 0x1234};
    const Payload out = encode(p);
    CHECK(bytes_of(out) == Bytes{0xC0, 0x12, 0x34});  // 1 10 00000, then the U16
    auto back = decode<PartialBits>(out.view());
    REQUIRE(back.ok);
    CHECK(back.value.flag);
    CHECK(back.value.code == 2);
    CHECK(back.value.after == 0x1234);
    // One byte short of the U16: the decoder notices.
    CHECK_FALSE(decode<PartialBits>(Bytes{0xC0, 0x12}).ok);
}

TEST_CASE("wide bitfields and reserved bits", "[orion][wire][bits]") {
    WideBits p{0xABC, 0xDE};
    const Payload out = encode(p);
    CHECK(bytes_of(out) == Bytes{0x0A, 0xBC, 0xDE});
    auto back = decode<WideBits>(Bytes{0xFA, 0xBC, 0xDE});  // reserved bits set: ignored
    REQUIRE(back.ok);
    CHECK(back.value.twelve == 0xABC);
    CHECK(back.value.eight == 0xDE);
    CHECK_FALSE(decode<WideBits>(Bytes{0xFA, 0xBC}).ok);
}

TEST_CASE("a bitfield value wider than its field saturates", "[orion][wire][bits]") {
    CrossingBits p{9, 200, 1, 0};  // a: 3 bits (max 7), b: 7 bits (max 127)
    auto back = decode<CrossingBits>(encode(p).view());
    REQUIRE(back.ok);
    CHECK(back.value.a == 7);
    CHECK(back.value.b == 127);
    CHECK(back.value.c == 1);
}

// --- strings and repeats -----------------------------------------------------------------

namespace {

struct Strings {
    std::string name;
    std::string fixed;
    std::uint8_t after = 0;
    template <class V>
    void fields(V& v) {
        v.string("name", name, 8);
        v.fixed_string("fixed", fixed, 4);
        v.field("after", after, u8);
    }
};

struct Repeat {
    std::vector<std::uint16_t> items;
    std::uint8_t after = 0;
    template <class V>
    void fields(V& v) {
        v.count("n", items, u8, 3);
        v.field("items", items, u16);
        v.field("after", after, u8);
    }
};

}  // namespace

TEST_CASE("strings are zero-terminated and at most max - 1 characters", "[orion][wire][string]") {
    Strings p{"abc", "xy", 7};
    CHECK(bytes_of(encode(p)) == Bytes{'a', 'b', 'c', 0, 'x', 'y', 0, 0, 7});
    auto back = decode<Strings>(encode(p).view());
    REQUIRE(back.ok);
    CHECK(back.value.name == "abc");
    CHECK(back.value.fixed == "xy");
    CHECK(back.value.after == 7);

    // No terminator within 8 bytes: 7 characters, and the 8th byte is the terminator's slot
    // (ProtoGen's stringFromBytes), so the next field stays where the encoder put it.
    const Bytes unterminated{'A', 'B', 'C', 'D', 'E', 'F', 'G', 'H', 'w', 'x', 'y', 'z', 9};
    auto cut = decode<Strings>(unterminated);
    REQUIRE(cut.ok);
    CHECK(cut.value.name == "ABCDEFG");
    CHECK(cut.value.fixed == "wxy");
    CHECK(cut.value.after == 9);
    // Re-encoding what we decoded gives the same fields back.
    auto again = decode<Strings>(encode(cut.value).view());
    REQUIRE(again.ok);
    CHECK(again.value.name == cut.value.name);
    CHECK(again.value.fixed == cut.value.fixed);
    CHECK(again.value.after == 9);
}

TEST_CASE("a repeat never writes more items than its count says", "[orion][wire][repeat]") {
    Repeat p{{1, 2, 3, 4, 5}, 9};
    Payload out;
    CHECK_FALSE(encode(p, out));  // more than the maximum: reported
    CHECK(bytes_of(out) == Bytes{3, 0, 1, 0, 2, 0, 3, 9});
    auto back = decode<Repeat>(out.view());
    REQUIRE(back.ok);
    CHECK(back.value.items == std::vector<std::uint16_t>{1, 2, 3});
    CHECK(back.value.after == 9);
}
