// IN1 / IN2 / IN3 (ICD 4.1): hand-written golden frames from the tables, the ICD's IN2
// example, decoding back, and the scaling rule (round half away from zero, saturate).
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/input.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using namespace viewpro_test;
using Catch::Matchers::WithinAbs;

namespace {

VehicleInput golden_vehicle() {
    VehicleInput v;
    v.time = {2024, 3, 15, 12, 34, 56};
    v.roll_deg = 5;
    v.pitch_deg = -3;
    v.yaw_deg = 120;
    v.lat_deg = 47.3977419;
    v.lon_deg = 8.5455938;
    v.alt_msl_m = 488.123;
    return v;
}

In3 golden_in3_fields() {
    In3 v;
    v.time = {2023, 11, 2, 7, 8, 9};
    v.lrf_m = 1234.567;
    v.pitch_deg = -12.345;
    v.yaw_deg = 270.5;
    v.lat_deg = -33.8688197;
    v.lon_deg = 151.2092955;
    v.alt_msl_m = 58.25;
    v.vel_ned_mps = {-1.5, 2.25, -0.75};
    return v;
}

InputFrame frame_of(const Bytes& b) {
    const auto f = make_input_frame(b);
    REQUIRE(f);
    return *f;
}

}  // namespace

TEST_CASE("IN1 encodes byte for byte", "[viewpro][in1]") {
    const Bytes wire = encode_vehicle(golden_vehicle());
    CHECK(wire.size() == in1_size);
    CHECK(wire == golden_in1);
}

TEST_CASE("IN2 encodes byte for byte", "[viewpro][in2]") {
    VehicleInput v = golden_vehicle();
    v.vel_ned_mps = std::array<double, 3>{12.34, -5.67, 0.89};
    const Bytes wire = encode_vehicle(v);
    CHECK(wire.size() == in2_size);
    CHECK(wire == golden_in2);
}

TEST_CASE("IN3 encodes byte for byte", "[viewpro][in3]") {
    const auto wire = encode_in3(golden_in3_fields());
    CHECK(Bytes(wire.begin(), wire.end()) == golden_in3);
}

TEST_CASE("the ICD's IN2 example, without its extra zeros, is our encoding", "[viewpro][in2]") {
    CHECK(icd_in2_example_50.size() == 50);
    CHECK(checksum_ok(icd_in2_example_50));  // the example's checksum sums its own bytes
    REQUIRE(icd_in2_example_40.size() == in2_size);
    CHECK(checksum_ok(icd_in2_example_40));

    const auto v = decode_vehicle(frame_of(icd_in2_example_40));
    REQUIRE(v);
    CHECK(v->time == DateTime{2021, 8, 7, 17, 27, 58});
    CHECK(v->roll_deg == 0);
    CHECK(v->pitch_deg == 0);
    CHECK(v->yaw_deg == 0);
    CHECK_THAT(v->lat_deg, WithinAbs(23.1234567, 1e-9));
    CHECK_THAT(v->lon_deg, WithinAbs(113.1234567, 1e-9));
    CHECK_THAT(v->alt_msl_m, WithinAbs(11.0, 1e-9));
    REQUIRE(v->vel_ned_mps);
    CHECK(*v->vel_ned_mps == std::array<double, 3>{0, 0, 0});
    CHECK(encode_vehicle(*v) == icd_in2_example_40);
}

TEST_CASE("IN1 and IN2 decode into contract units", "[viewpro][in1][in2]") {
    const InputFrame f1 = frame_of(golden_in1);
    CHECK(f1.kind == InputFrame::Kind::in1);
    const auto v1 = decode_vehicle(f1);
    REQUIRE(v1);
    CHECK(v1->time == DateTime{2024, 3, 15, 12, 34, 56});
    CHECK_THAT(v1->roll_deg, WithinAbs(5, 1e-5));  // float radians
    CHECK_THAT(v1->pitch_deg, WithinAbs(-3, 1e-5));
    CHECK_THAT(v1->yaw_deg, WithinAbs(120, 1e-5));
    CHECK_THAT(v1->lat_deg, WithinAbs(47.3977419, 1e-9));
    CHECK_THAT(v1->lon_deg, WithinAbs(8.5455938, 1e-9));
    CHECK_THAT(v1->alt_msl_m, WithinAbs(488.123, 1e-9));
    CHECK_FALSE(v1->vel_ned_mps);
    CHECK_FALSE(decode_in3(f1));

    const InputFrame f2 = frame_of(golden_in2);
    CHECK(f2.kind == InputFrame::Kind::in2);
    const auto v2 = decode_vehicle(f2);
    REQUIRE(v2);
    REQUIRE(v2->vel_ned_mps);
    CHECK_THAT((*v2->vel_ned_mps)[0], WithinAbs(12.34, 1e-9));
    CHECK_THAT((*v2->vel_ned_mps)[1], WithinAbs(-5.67, 1e-9));
    CHECK_THAT((*v2->vel_ned_mps)[2], WithinAbs(0.89, 1e-9));
    // Decoded values encode to the same bytes.
    CHECK(encode_vehicle(*v1) == golden_in1);
    CHECK(encode_vehicle(*v2) == golden_in2);
}

TEST_CASE("IN3 is told from IN2 by byte 3 and decodes", "[viewpro][in3]") {
    const InputFrame f = frame_of(golden_in3);
    CHECK(f.kind == InputFrame::Kind::in3);
    CHECK_FALSE(decode_vehicle(f));
    const auto v = decode_in3(f);
    REQUIRE(v);
    CHECK(v->time == DateTime{2023, 11, 2, 7, 8, 9});
    CHECK_THAT(v->lrf_m, WithinAbs(1234.567, 1e-9));
    CHECK_THAT(v->pitch_deg, WithinAbs(-12.345, 1e-9));
    CHECK_THAT(v->yaw_deg, WithinAbs(270.5, 1e-9));
    CHECK_THAT(v->lat_deg, WithinAbs(-33.8688197, 1e-9));
    CHECK_THAT(v->lon_deg, WithinAbs(151.2092955, 1e-9));
    CHECK_THAT(v->alt_msl_m, WithinAbs(58.25, 1e-9));
    CHECK_THAT(v->vel_ned_mps[0], WithinAbs(-1.5, 1e-9));
    CHECK_THAT(v->vel_ned_mps[1], WithinAbs(2.25, 1e-9));
    CHECK_THAT(v->vel_ned_mps[2], WithinAbs(-0.75, 1e-9));
    const auto again = encode_in3(*v);
    CHECK(Bytes(again.begin(), again.end()) == golden_in3);
}

TEST_CASE("scaled input fields round half away from zero and saturate", "[viewpro][scaling]") {
    VehicleInput v;
    v.lat_deg = 1e9;        // beyond int32 degE7 -> INT32_MAX
    v.lon_deg = -1e9;       // -> INT32_MIN
    v.alt_msl_m = -0.0625;  // -62.5 mm (exact in binary) -> -63
    v.vel_ned_mps = std::array<double, 3>{400.0, -400.0, 0.125};  // int16 saturates; 12.5 -> 13
    const Bytes w = encode_vehicle(v);
    CHECK(Bytes(w.begin() + 21, w.begin() + 25) == hex("FF FF FF 7F"));
    CHECK(Bytes(w.begin() + 25, w.begin() + 29) == hex("00 00 00 80"));
    CHECK(Bytes(w.begin() + 29, w.begin() + 33) == hex("C1 FF FF FF"));
    CHECK(Bytes(w.begin() + 33, w.begin() + 39) == hex("FF 7F 00 80 0D 00"));
    CHECK(checksum_ok(w));

    In3 i;
    i.lrf_m = -5;        // uint32 mm: below 0 saturates to 0
    i.time.year = 1999;  // year byte: years before 2000 clamp to 0
    const auto w3 = encode_in3(i);
    CHECK(w3[2] == 0);
    CHECK(Bytes(w3.begin() + 9, w3.begin() + 13) == hex("00 00 00 00"));
    i.time.year = 2400;
    CHECK(encode_in3(i)[2] == 255);
}

TEST_CASE("decoders refuse frames of another kind", "[viewpro][input]") {
    const InputFrame mode = frame_of(hex("AA 55 0F 51 FF"));
    CHECK(mode.kind == InputFrame::Kind::mode);
    CHECK_FALSE(decode_vehicle(mode));
    CHECK_FALSE(decode_in3(mode));
    CHECK_FALSE(decode_shift(mode));
    REQUIRE(decode_mode(mode));
    CHECK(mode_byte(*decode_mode(mode)) == 0x51);

    const InputFrame yaw = frame_of(hex("AA 55 06 9C FF"));
    CHECK(yaw.kind == InputFrame::Kind::yaw_shift);
    CHECK(decode_shift(yaw) == std::int8_t{-100});
    CHECK_FALSE(decode_mode(yaw));
    const InputFrame pitch = frame_of(hex("AA 55 36 32 FF"));
    CHECK(pitch.kind == InputFrame::Kind::pitch_shift);
    CHECK(decode_shift(pitch) == std::int8_t{50});

    // A hand-made frame whose size does not fit its kind is malformed.
    InputFrame wrong = frame_of(golden_in2);
    wrong.kind = InputFrame::Kind::in1;
    CHECK_FALSE(decode_vehicle(wrong));
    wrong.kind = InputFrame::Kind::mode;
    CHECK_FALSE(decode_mode(wrong));
}

TEST_CASE("make_input_frame checks one whole frame", "[viewpro][input]") {
    CHECK(make_input_frame(golden_in1));
    CHECK_FALSE(make_input_frame(Bytes(golden_in1.begin(), golden_in1.end() - 1)));  // short
    CHECK_FALSE(make_input_frame(concat({golden_in1, {0x00}})));                     // long
    Bytes bad = golden_in2;
    bad[20] ^= 0x01;
    CHECK_FALSE(make_input_frame(bad));                    // checksum
    CHECK_FALSE(make_input_frame(hex("AA 55 0F 51 FE")));  // end byte
    CHECK_FALSE(make_input_frame(hex("AA 55 07 51 FF")));  // unknown command
    CHECK_FALSE(make_input_frame(hex("F9 FA 00")));
    CHECK_FALSE(make_input_frame({}));
    CHECK(to_string(InputFrame::Kind::in3) == "in3");
    CHECK(to_string(InputFrame::Kind::yaw_shift) == "yaw_shift");
}
