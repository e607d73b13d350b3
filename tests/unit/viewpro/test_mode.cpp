// Mode and shift commands (ICD sections 1 and 5): the ICD's examples byte for byte.
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/mode.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using viewpro_test::Bytes;
using viewpro_test::hex;

namespace {

Bytes bytes(const Command5& c) {
    return Bytes(c.begin(), c.end());
}

Mode mode(Osd osd, bool network, bool serial, OutFormat format) {
    Mode m;
    m.osd = osd;
    m.network = network;
    m.serial = serial;
    m.format = format;
    return m;
}

}  // namespace

TEST_CASE("mode command examples of ICD section 1 encode byte for byte", "[viewpro][mode]") {
    // Section 1 header: AA 55 0F 31 FF, target on OSD, serial OUT2.
    CHECK(bytes(encode_mode(mode(Osd::target, false, true, OutFormat::out2))) ==
          hex("AA 55 0F 31 FF"));
    // 1.1 Display target, serial port outputs OUT4.
    CHECK(bytes(encode_mode(mode(Osd::target, false, true, OutFormat::out4))) ==
          hex("AA 55 0F 71 FF"));
    // 1.2 Display target, serial port and RJ45 output OUT3.
    CHECK(bytes(encode_mode(mode(Osd::target, true, true, OutFormat::out3))) ==
          hex("AA 55 0F 59 FF"));
    // 1.3 Display UAV, serial port outputs OUT2.
    CHECK(bytes(encode_mode(mode(Osd::uav, false, true, OutFormat::out2))) ==
          hex("AA 55 0F 30 FF"));
    // 1.4 Display target, serial port outputs OUT1.
    CHECK(bytes(encode_mode(mode(Osd::target, false, true, OutFormat::out1))) ==
          hex("AA 55 0F 11 FF"));
    // 1.6 Display target, no output (the gimbal's default).
    CHECK(bytes(encode_mode(mode(Osd::target, false, false, OutFormat::out1))) ==
          hex("AA 55 0F 01 FF"));
    CHECK(gimbal_default_mode_byte == 0x01);
}

TEST_CASE("mode example 1.5 follows the bit table, not its text (errata)", "[viewpro][mode]") {
    // 79 = 0111 1001: the serial bit (4) is set as well as the network bit (3).
    const Mode m = decode_mode_byte(0x79);
    CHECK(m == mode(Osd::target, true, true, OutFormat::out4));
    CHECK(bytes(encode_mode(m)) == hex("AA 55 0F 79 FF"));
    // What the text describes, RJ45 only, is 0x69.
    CHECK(bytes(encode_mode(mode(Osd::target, true, false, OutFormat::out4))) ==
          hex("AA 55 0F 69 FF"));
}

TEST_CASE("every defined mode byte decodes and encodes back", "[viewpro][mode]") {
    int defined = 0;
    for (int b = 0; b < 256; ++b) {
        const auto byte = static_cast<std::uint8_t>(b);
        const bool reserved_clear = (byte & 0x06) == 0;
        if (!mode_byte_is_defined(byte)) {
            CHECK(b >= 0x80);
            continue;
        }
        CHECK(b < 0x80);
        ++defined;
        const Mode m = decode_mode_byte(byte);
        // Reserved bits 1..2 are not kept.
        CHECK((mode_byte(m) == byte) == reserved_clear);
        CHECK(mode_byte(m) == (byte & 0xF9));
    }
    CHECK(defined == 128);
}

TEST_CASE("mode fields map to their bits", "[viewpro][mode]") {
    CHECK(mode_byte(mode(Osd::uav, false, false, OutFormat::out1)) == 0x00);
    CHECK(mode_byte(mode(Osd::target, false, false, OutFormat::out1)) == 0x01);
    CHECK(mode_byte(mode(Osd::uav, true, false, OutFormat::out1)) == 0x08);
    CHECK(mode_byte(mode(Osd::uav, false, true, OutFormat::out1)) == 0x10);
    CHECK(mode_byte(mode(Osd::uav, false, false, OutFormat::out2)) == 0x20);
    CHECK(mode_byte(mode(Osd::uav, false, false, OutFormat::out3)) == 0x40);
    CHECK(mode_byte(mode(Osd::uav, false, false, OutFormat::out4)) == 0x60);
    // The default Mode is what gimbald sends unless configured: target, serial OUT3.
    CHECK(mode_byte(Mode{}) == 0x51);
}

TEST_CASE("shift command examples of ICD section 5 encode byte for byte", "[viewpro][shift]") {
    CHECK(bytes(encode_yaw_shift(-100)) == hex("AA 55 06 9C FF"));
    CHECK(bytes(encode_yaw_shift(100)) == hex("AA 55 06 64 FF"));
    CHECK(bytes(encode_pitch_shift(-100)) == hex("AA 55 36 9C FF"));
    CHECK(bytes(encode_pitch_shift(100)) == hex("AA 55 36 64 FF"));
    CHECK(bytes(encode_pitch_shift(50)) == hex("AA 55 36 32 FF"));
    CHECK(bytes(encode_yaw_shift(-128)) == hex("AA 55 06 80 FF"));
    CHECK(bytes(encode_pitch_shift(127)) == hex("AA 55 36 7F FF"));
}

TEST_CASE("output format and OSD names", "[viewpro][mode]") {
    CHECK(to_string(OutFormat::out1) == "out1");
    CHECK(to_string(OutFormat::out4) == "out4");
    CHECK(to_string(Osd::uav) == "uav");
    CHECK(to_string(Osd::target) == "target");
    for (const OutFormat f : {OutFormat::out1, OutFormat::out2, OutFormat::out3, OutFormat::out4})
        CHECK(parse_out_format(to_string(f)) == f);
    CHECK_FALSE(parse_out_format("out5"));
    CHECK_FALSE(parse_out_format("OUT1"));
    CHECK_FALSE(parse_out_format(""));
    CHECK(parse_osd("uav") == Osd::uav);
    CHECK(parse_osd("target") == Osd::target);
    CHECK_FALSE(parse_osd("both"));
}
