// Codec strings for browser decoders from parameter sets produced by x264 and x265; the
// expected strings are what FFmpeg's own writers derive from the same streams (MP4 `avcC` /
// `hvcC` boxes as WebCodecs reads them).
#include <catch2/catch.hpp>

#include "ts_builder.hpp"
#include "video/codec_string.hpp"

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

TEST_CASE("Codec string: H.264 avc1.PPCCLL from the SPS", "[video][codec_string]") {
    // x264 High 1080p30, Constrained Baseline 640x360 (the simulator's profile is 42C01E).
    CHECK(v::codec_string(v::Codec::h264,
                          hex("67640028acd940780227e5c044000003000400000300f03c60c658")) ==
          "avc1.640028");
    CHECK(v::codec_string(v::Codec::h264,
                          hex("6742c016d900a02ff970110000030001000003001e0f162e48")) ==
          "avc1.42C016");
    CHECK_FALSE(v::codec_string(v::Codec::h264, hex("68ebe3cb22c0")));  // a PPS
    CHECK_FALSE(v::codec_string(v::Codec::h264, hex("6742")));          // cut short
    CHECK_FALSE(v::codec_string(v::Codec::h264, Bytes{}));
}

TEST_CASE("Codec string: H.265 hvc1 from the SPS's profile_tier_level", "[video][codec_string]") {
    // x265 Main 1080p: profile 1, compatibility flags 0x60000000 (reversed: 6), level 4.0
    // (120), constraint byte 0x90.
    CHECK(v::codec_string(
              v::Codec::h265,
              hex("420101016000000300900000030000030078a003c08010e596566924caf0168080000003008000"
                  "000f04")) == "hvc1.1.6.L120.90");
    // x265 Main 4:4:4 (RExt, profile 4): two constraint bytes.
    CHECK(v::codec_string(v::Codec::h265,
                          hex("4201010408000003009e0800000300007890007810021cb2cacd24995ffe0006000"
                              "8dc0808001000000300100000301e080")) == "hvc1.4.10.L120.9E.08");
    CHECK_FALSE(v::codec_string(v::Codec::h265, hex("40010c01ffff0160")));  // a VPS
    CHECK_FALSE(v::codec_string(v::Codec::h265, hex("42010101")));          // cut short
}

TEST_CASE("Codec string: the first SPS of an access unit", "[video][codec_string]") {
    const Bytes key = gimbal::test::h264_au(true);
    const auto s = v::find_codec_string(v::Codec::h264, key);
    REQUIRE(s);
    CHECK(s->rfind("avc1.", 0) == 0);
    CHECK(s->size() == 11);
    CHECK_FALSE(v::find_codec_string(v::Codec::h264, gimbal::test::h264_au(false)));
}
