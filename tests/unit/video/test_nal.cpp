// H.264/H.265 bitstream helpers: Annex B splitting, key frames, parameter sets, AVCC/HVCC
// to Annex B, and SPS parsing against parameter sets produced by x264 and x265 (the
// expected sizes and rates are what ffprobe reported for the same streams).
#include <catch2/catch.hpp>

#include "ts_builder.hpp"
#include "video/bit_reader.hpp"
#include "video/nal.hpp"

namespace v = gimbal::video;
using gimbal::test::Bytes;

namespace {

Bytes hex(std::string_view s) {
    Bytes b;
    for (std::size_t i = 0; i + 1 < s.size(); i += 2)
        b.push_back(static_cast<std::uint8_t>(std::stoi(std::string(s.substr(i, 2)), nullptr, 16)));
    return b;
}

}  // namespace

TEST_CASE("Annex B: NAL units with 3- and 4-byte start codes, trailing zeros", "[video][nal]") {
    const Bytes s = {0xAA, 0, 0, 1,    0x09, 0xF0, 0, 0, 0,    0,    1,    0x67, 0x42, 0x00,
                     0,    0, 1, 0x68, 0xCE, 0,    0, 1, 0x65, 0x00, 0x00, 0x03, 0x01, 0x00};
    const auto nals = v::split_annexb(s);
    REQUIRE(nals.size() == 4);
    CHECK(Bytes(nals[0].begin(), nals[0].end()) == Bytes{0x09, 0xF0});
    CHECK(Bytes(nals[1].begin(), nals[1].end()) == Bytes{0x67, 0x42});
    CHECK(Bytes(nals[2].begin(), nals[2].end()) == Bytes{0x68, 0xCE});
    CHECK(Bytes(nals[3].begin(), nals[3].end()) == Bytes{0x65, 0x00, 0x00, 0x03, 0x01});
    CHECK(v::split_annexb(Bytes{1, 2, 3}).empty());
    CHECK(v::split_annexb(Bytes{0, 0, 1}).empty());
}

TEST_CASE("Key frames: IDR (H.264), IRAP (H.265), decided by the first slice", "[video][nal]") {
    CHECK(v::is_key_frame(v::Codec::h264, gimbal::test::h264_au(true)));
    CHECK_FALSE(v::is_key_frame(v::Codec::h264, gimbal::test::h264_au(false)));
    // H.265: AUD (35), VPS/SPS/PPS, IDR_W_RADL (19) / CRA (21) / TRAIL_R (1).
    const Bytes idr = {0,    0,    1,    0x46, 0x01, 0x50, 0,    0,    1,
                       0x40, 0x01, 0x0C, 0,    0,    1,    0x26, 0x01, 0xAF};
    const Bytes cra = {0, 0, 1, 0x2A, 0x01, 0xAF};
    const Bytes trail = {0, 0, 1, 0x02, 0x01, 0xD0};
    CHECK(v::is_key_frame(v::Codec::h265, idr));
    CHECK(v::is_key_frame(v::Codec::h265, cra));
    CHECK_FALSE(v::is_key_frame(v::Codec::h265, trail));
    CHECK(v::nal_type(v::Codec::h265, Bytes{0x40, 0x01}) == v::h265::vps);
    CHECK(v::nal_type(v::Codec::h264, Bytes{0x67}) == v::h264::sps);
}

TEST_CASE("RBSP: emulation prevention removed; Exp-Golomb codes", "[video][nal]") {
    CHECK(v::unescape_rbsp(Bytes{0x00, 0x00, 0x03, 0x01, 0x00, 0x00, 0x03}) ==
          Bytes{0x00, 0x00, 0x01, 0x00, 0x00});
    // 1 | 010 | 011 | 00100 | 00101 -> ue 0, 1, 2, 3, se(4) = -2
    const Bytes bits = {0b10100110, 0b01000010, 0b10000000};
    v::BitReader r(bits);
    CHECK(r.ue() == 0);
    CHECK(r.ue() == 1);
    CHECK(r.ue() == 2);
    CHECK(r.ue() == 3);
    CHECK(r.se() == -2);
    CHECK_FALSE(r.failed());
    r.bits(9);
    CHECK(r.failed());
}

TEST_CASE("SPS: width, height, frame rate from x264 and x265 parameter sets", "[video][sps]") {
    struct Case {
        v::Codec codec;
        const char* sps;
        int width, height;
        double fps;
    };
    const Case cases[] = {
        // x264 High 4:2:0, 1920x1080 (1088 cropped), 30 fps.
        {v::Codec::h264, "67640028acd940780227e5c044000003000400000300f03c60c658", 1920, 1080, 30},
        // x264 Constrained Baseline 640x360 (368 cropped), 15 fps.
        {v::Codec::h264, "6742c016d900a02ff970110000030001000003001e0f162e48", 640, 360, 15},
        // x264 High 4:4:4 Predictive, 1920x1080, 320x240 25 fps, 640x360.
        {v::Codec::h264, "67f40028919b280f0044fc4ffe0006000820000003002000000781e30632c0", 1920,
         1080, 30},
        {v::Codec::h264, "67f4000d919b28283f6022000003000200000300641e28532c", 320, 240, 25},
        {v::Codec::h264, "67f40016919b281405ff13ff8001800208000003000800000300f078b16cb0", 640, 360,
         15},
        // x264 interlaced (frame_mbs_only 0) PAL 720x576, 25 frames/s.
        {v::Codec::h264, "67f4001e919b2816849bff0010000f1000000300100000030321f1429960", 720, 576,
         25},
        // x265 Main 1920x1080 (conformance window), 30 fps; 4:4:4 1080p and 640x360 15 fps.
        {v::Codec::h265,
         "420101016000000300900000030000030078a003c08010e596566924caf0168080000003008000000f04",
         1920, 1080, 30},
        {v::Codec::h265,
         "4201010408000003009e0800000300007890007810021cb2cacd24995ffe00060008dc0808001000000300100"
         "0000301e080",
         1920, 1080, 30},
        {v::Codec::h265,
         "4201010408000003009e0800000300003f9000a0402d2cb2b3492657ff8001800237020200040000030004000"
         "003003c20",
         640, 360, 15},
    };
    for (const Case& c : cases) {
        CAPTURE(c.sps);
        const auto f = v::parse_sps(c.codec, hex(c.sps));
        REQUIRE(f);
        CHECK(f->width == c.width);
        CHECK(f->height == c.height);
        REQUIRE(f->fps);
        CHECK(*f->fps == Approx(c.fps));
        // Every cut short of the whole SPS is refused or still reports the same size (the
        // VUI is optional at the end) - never a wrong size.
        const Bytes whole = hex(c.sps);
        for (std::size_t n = 0; n < whole.size(); ++n) {
            const auto cut = v::parse_sps(c.codec, std::span(whole).first(n));
            if (cut) {
                CHECK(cut->width == c.width);
                CHECK(cut->height == c.height);
            }
        }
    }
    CHECK_FALSE(v::parse_sps(v::Codec::h264, hex("68ebe3cb22c0")));  // a PPS
    CHECK(v::find_format(v::Codec::h264, gimbal::test::h264_au(true)) ==
          v::VideoFormat{640, 360, 15.0});
    CHECK_FALSE(v::find_format(v::Codec::h264, gimbal::test::h264_au(false)));
}

TEST_CASE("avcC/hvcC extradata and length-prefixed samples to Annex B", "[video][nal]") {
    const Bytes sps = hex("6742c016d900a02ff970110000030001000003001e0f162e48");
    const Bytes pps = hex("68cb83cb20");
    // avcC (ISO 14496-15 5.3.3.1): version 1, profile, compat, level, 111111 + lengthSize-1
    // (3 -> 4 bytes), 111 + numSPS 1, SPS length + SPS, numPPS 1, PPS length + PPS.
    Bytes avcc = {0x01, 0x42, 0xC0, 0x16, 0xFF, 0xE1, 0x00, static_cast<std::uint8_t>(sps.size())};
    avcc.insert(avcc.end(), sps.begin(), sps.end());
    avcc.insert(avcc.end(), {0x01, 0x00, static_cast<std::uint8_t>(pps.size())});
    avcc.insert(avcc.end(), pps.begin(), pps.end());
    const auto ex = v::parse_extradata(v::Codec::h264, avcc);
    REQUIRE(ex);
    CHECK(ex->length_size == 4);
    REQUIRE(ex->sets.nals.size() == 2);
    CHECK(ex->sets.nals[0] == sps);
    CHECK(ex->sets.nals[1] == pps);
    CHECK_FALSE(v::parse_extradata(v::Codec::h264, std::span(avcc).first(avcc.size() - 1)));

    // The same sets given as Annex B (RTSP sprop-parameter-sets through libavformat).
    const auto annexb = v::parse_extradata(v::Codec::h264, ex->sets.annexb());
    REQUIRE(annexb);
    CHECK(annexb->length_size == 0);
    CHECK(annexb->sets.nals == ex->sets.nals);

    // hvcC (14496-15 8.3.3.1): 22 bytes of configuration, numOfArrays, then per array
    // type, numNalus, length + NAL.
    const Bytes vps = hex("40010c01ffff016000000300900000030000030078959809");
    const Bytes hsps =
        hex("420101016000000300900000030000030078a003c08010e596566924caf0168080000003008000000f04");
    const Bytes hpps = hex("4401c172b46240");
    Bytes hvcc(22, 0);
    hvcc[0] = 1;
    hvcc[21] = 0xFF;  // ..., lengthSizeMinusOne 3
    hvcc.push_back(3);
    for (const Bytes* nal : {&vps, &hsps, &hpps}) {
        hvcc.insert(hvcc.end(), {static_cast<std::uint8_t>(0x80 | ((*nal)[0] >> 1)), 0x00, 0x01,
                                 0x00, static_cast<std::uint8_t>(nal->size())});
        hvcc.insert(hvcc.end(), nal->begin(), nal->end());
    }
    const auto hex_ex = v::parse_extradata(v::Codec::h265, hvcc);
    REQUIRE(hex_ex);
    CHECK(hex_ex->length_size == 4);
    REQUIRE(hex_ex->sets.nals.size() == 3);
    CHECK(hex_ex->sets.has_sps(v::Codec::h265));
    CHECK(v::parse_sps(v::Codec::h265, hex_ex->sets.nals[1])->width == 1920);

    // Length-prefixed sample: 2-byte lengths.
    const Bytes sample = {0x00, 0x02, 0x09, 0xF0, 0x00, 0x03, 0x65, 0x88, 0x84};
    const auto converted = v::length_prefixed_to_annexb(sample, 2);
    REQUIRE(converted);
    CHECK(*converted == Bytes{0, 0, 0, 1, 0x09, 0xF0, 0, 0, 0, 1, 0x65, 0x88, 0x84});
    CHECK_FALSE(v::length_prefixed_to_annexb(std::span(sample).first(8), 2));
    CHECK_FALSE(v::length_prefixed_to_annexb(sample, 3 + 2));
}

TEST_CASE("Parameter sets go in front of key frames that lack them", "[video][nal]") {
    v::ParameterSets sets;
    const Bytes key = gimbal::test::h264_au(true);
    for (const auto nal : v::split_annexb(key)) sets.update(v::Codec::h264, nal);
    REQUIRE(sets.nals.size() == 2);
    // IDR without SPS/PPS: AUD, then the sets, then the slice.
    const Bytes bare = {0, 0, 0, 1, 0x09, 0xF0, 0, 0, 0, 1, 0x65, 0x88, 0x80};
    const Bytes fixed = v::with_parameter_sets(v::Codec::h264, bare, sets);
    const auto nals = v::split_annexb(fixed);
    REQUIRE(nals.size() == 4);
    CHECK(v::nal_type(v::Codec::h264, nals[0]) == v::h264::aud);
    CHECK(v::nal_type(v::Codec::h264, nals[1]) == v::h264::sps);
    CHECK(v::nal_type(v::Codec::h264, nals[2]) == v::h264::pps);
    CHECK(v::nal_type(v::Codec::h264, nals[3]) == v::h264::idr);
    // Non-key frames and key frames that carry their own sets are left alone.
    const Bytes p = gimbal::test::h264_au(false);
    CHECK(v::with_parameter_sets(v::Codec::h264, p, sets) == p);
    const Bytes k = gimbal::test::h264_au(true);
    CHECK(v::with_parameter_sets(v::Codec::h264, k, sets) == k);
    // An in-band SPS replaces the stored one of the same type.
    sets.update(v::Codec::h264, Bytes{0x67, 0x01});
    CHECK(sets.nals.size() == 2);
    CHECK(sets.nals[0] == Bytes{0x67, 0x01});
}
