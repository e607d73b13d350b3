// OUT1..OUT4 (ICD 4.2): the ICD's OUT1 example, hand-written golden frames from the tables,
// encoding back, and malformed frames.
#include <catch2/catch.hpp>

#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/output.hpp"
#include "vectors.hpp"

using namespace gimbal::viewpro;
using namespace viewpro_test;
using Catch::Matchers::WithinAbs;

namespace {

Output decoded(const Bytes& wire) {
    const auto frame = make_output_frame(wire);
    REQUIRE(frame);
    const auto out = decode_output(*frame);
    REQUIRE(out);
    return *out;
}

// OUT2 and OUT3 carry the same fields (OUT3 rounds lat/lon to degE7).
void check_out23_fields(const Output& o, double latlon_tol) {
    CHECK(o.time == DateTime{2022, 6, 30, 23, 59, 58});
    CHECK(o.zoom == 1234);
    CHECK_THAT(*o.gimbal_roll_deg, WithinAbs(1.5, 1e-5));
    CHECK_THAT(*o.gimbal_pitch_deg, WithinAbs(-30, 1e-5));
    CHECK_THAT(*o.gimbal_yaw_deg, WithinAbs(45, 1e-5));
    CHECK(*o.lrf_m == 523.25);
    CHECK_THAT(*o.uav_roll_deg, WithinAbs(-2, 1e-5));
    CHECK_THAT(*o.uav_pitch_deg, WithinAbs(4, 1e-5));
    CHECK_THAT(*o.uav_yaw_deg, WithinAbs(-160, 1e-5));
    CHECK_THAT(*o.uav_alt_msl_m, WithinAbs(1234.567, 1e-9));
    CHECK_THAT(*o.uav_lat_deg, WithinAbs(6.9428789, latlon_tol));
    CHECK_THAT(*o.uav_lon_deg, WithinAbs(79.8812446, latlon_tol));
    CHECK_THAT(*o.target_lat_deg, WithinAbs(6.95, latlon_tol));
    CHECK_THAT(*o.target_lon_deg, WithinAbs(79.89, latlon_tol));
    CHECK_FALSE(o.target_alt_msl_m);
}

Output out23_fields(OutFormat format) {
    Output o;
    o.format = format;
    o.time = DateTime{2022, 6, 30, 23, 59, 58};
    o.zoom = 1234;
    o.gimbal_roll_deg = 1.5;
    o.gimbal_pitch_deg = -30;
    o.gimbal_yaw_deg = 45;
    o.lrf_m = 523.25;
    o.uav_roll_deg = -2;
    o.uav_pitch_deg = 4;
    o.uav_yaw_deg = -160;
    o.uav_alt_msl_m = 1234.567;
    o.uav_lat_deg = 6.9428789;
    o.uav_lon_deg = 79.8812446;
    o.target_lat_deg = 6.95;
    o.target_lon_deg = 79.89;
    return o;
}

}  // namespace

TEST_CASE("the ICD's OUT1 feedback example decodes", "[viewpro][out1]") {
    const Output o = decoded(icd_out1);
    CHECK(o.format == OutFormat::out1);
    CHECK(*o.gimbal_pitch_deg == 27.0);
    CHECK(*o.gimbal_yaw_deg == 16.0);
    CHECK(*o.lrf_m == 0.0);
    // OUT1 carries longitude before latitude.
    CHECK_THAT(*o.target_lon_deg, WithinAbs(79.8812446, 1e-12));
    CHECK_THAT(*o.target_lat_deg, WithinAbs(6.9428789, 1e-12));
    // Nothing OUT1 lacks is filled in.
    CHECK_FALSE(o.time);
    CHECK_FALSE(o.zoom);
    CHECK_FALSE(o.gimbal_roll_deg);
    CHECK_FALSE(o.uav_lat_deg);
    CHECK_FALSE(o.uav_alt_msl_m);
    CHECK_FALSE(o.target_alt_msl_m);
    CHECK(encode_output(o) == icd_out1);
}

TEST_CASE("OUT2 decodes and encodes byte for byte", "[viewpro][out2]") {
    const Output o = decoded(golden_out2);
    CHECK(o.format == OutFormat::out2);
    check_out23_fields(o, 1e-9);  // double radians
    CHECK(encode_output(o) == golden_out2);
    CHECK(encode_output(out23_fields(OutFormat::out2)) == golden_out2);
}

TEST_CASE("OUT3 decodes and encodes byte for byte", "[viewpro][out3]") {
    const Output o = decoded(golden_out3);
    CHECK(o.format == OutFormat::out3);
    check_out23_fields(o, 1e-9);
    CHECK(encode_output(o) == golden_out3);
    CHECK(encode_output(out23_fields(OutFormat::out3)) == golden_out3);
}

TEST_CASE("OUT4 is told from OUT3 by byte 3, decodes and encodes", "[viewpro][out4]") {
    const Output o = decoded(golden_out4);
    CHECK(o.format == OutFormat::out4);
    CHECK(o.time == DateTime{2025, 1, 2, 3, 4, 5});
    CHECK(o.zoom == 4321);
    CHECK_THAT(*o.gimbal_roll_deg, WithinAbs(0.5, 1e-12));
    CHECK_THAT(*o.gimbal_pitch_deg, WithinAbs(-45.123, 1e-12));
    CHECK_THAT(*o.gimbal_yaw_deg, WithinAbs(90.001, 1e-12));
    CHECK_THAT(*o.lrf_m, WithinAbs(987.654, 1e-12));
    CHECK_THAT(*o.target_alt_msl_m, WithinAbs(12.345, 1e-12));
    CHECK_THAT(*o.uav_pitch_deg, WithinAbs(2.5, 1e-12));
    CHECK_THAT(*o.uav_yaw_deg, WithinAbs(-170.25, 1e-12));
    CHECK_THAT(*o.uav_alt_msl_m, WithinAbs(321.5, 1e-12));
    CHECK_THAT(*o.uav_lat_deg, WithinAbs(-22.9068467, 1e-12));
    CHECK_THAT(*o.uav_lon_deg, WithinAbs(-43.1728965, 1e-12));
    CHECK_THAT(*o.target_lat_deg, WithinAbs(-22.91, 1e-12));
    CHECK_THAT(*o.target_lon_deg, WithinAbs(-43.17, 1e-12));
    CHECK_FALSE(o.uav_roll_deg);  // OUT4 has no UAV roll
    CHECK(encode_output(o) == golden_out4);
}

TEST_CASE("missing fields encode as zero", "[viewpro][output]") {
    for (const OutFormat f : {OutFormat::out1, OutFormat::out2, OutFormat::out3, OutFormat::out4}) {
        Output o;
        o.format = f;
        const Bytes w = encode_output(o);
        CAPTURE(to_string(f));
        REQUIRE(w.size() == output_size(f));
        CHECK(w[0] == output_header);
        CHECK(w[1] == output_id(f));
        CHECK(checksum_ok(w));
        const auto back = make_output_frame(w);
        REQUIRE(back);
        CHECK(back->format == f);
        const auto d = decode_output(*back);
        REQUIRE(d);
        CHECK(d->target_lat_deg.value_or(1) == 0);
    }
}

TEST_CASE("decode_output refuses malformed frames", "[viewpro][output]") {
    auto frame = make_output_frame(golden_out3);
    REQUIRE(frame);
    CHECK(decode_output(*frame));

    OutputFrame f = *frame;
    f.format = OutFormat::out4;  // byte 3 is not FF
    CHECK_FALSE(decode_output(f));
    f = *frame;
    f.format = OutFormat::out2;  // wrong length and id
    CHECK_FALSE(decode_output(f));
    f = *frame;
    f.bytes[10] ^= 0x01;  // checksum
    CHECK_FALSE(decode_output(f));
    f = *frame;
    f.size = 59;
    CHECK_FALSE(decode_output(f));

    auto out4 = make_output_frame(golden_out4);
    REQUIRE(out4);
    out4->format = OutFormat::out3;  // byte 3 is FF
    CHECK_FALSE(decode_output(*out4));
}

TEST_CASE("make_output_frame checks one whole frame", "[viewpro][output]") {
    CHECK(make_output_frame(icd_out1));
    CHECK_FALSE(make_output_frame(Bytes(icd_out1.begin(), icd_out1.end() - 1)));
    CHECK_FALSE(make_output_frame(concat({icd_out1, {0xFE}})));
    Bytes bad = icd_out1;
    bad.back() ^= 0xFF;
    CHECK_FALSE(make_output_frame(bad));
    bad = icd_out1;
    bad[1] = 0xFA;  // unknown id
    bad.back() = sum8(std::span(bad).first(bad.size() - 1));
    CHECK_FALSE(make_output_frame(bad));
    CHECK_FALSE(make_output_frame({}));
}

TEST_CASE("the ICD's broken OUT2 and OUT3 examples are not frames (errata)", "[viewpro][output]") {
    // OUT2: 75 bytes, checksum wrong. OUT3: truncated.
    const Bytes out2_example = hex(
        "FE FC E3 07 08 15 07 16 00 60 26 00 00 00 00 3A 46 F1 3E 35 FA 8E 3E 00 00 00 00 CD CC 4C "
        "3E CD CC 4C 3F 00 00 00 3F B0 BF FF 9C BB 70 46 A3 03 BF 3F 18 23 12 39 7F 4E F6 3F 1C 52 "
        "6C 9A 65 05 BF 3F 60 FA E1 FA 9A 4E F6 3F A7");
    CHECK(out2_example.size() == 75);
    CHECK_FALSE(make_output_frame(out2_example));
    const Bytes out3_example =
        hex("FE FD E5 07 02 05 0D 13 31 00 00 00 00 00 50 77 56 BD C2 B8 32 3F 7C 00 00 DE 40 F9 "
            "40 4C");
    CHECK_FALSE(make_output_frame(out3_example));
}
