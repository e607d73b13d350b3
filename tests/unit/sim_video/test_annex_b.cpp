// Annex B parsing and the RFC 6381 codec string.
#include <catch2/catch.hpp>

#include "sim_video/annex_b.hpp"

using namespace gimbal::sim_video;

TEST_CASE("annex b: NAL units after 3- and 4-byte start codes", "[sim_video][annex_b]") {
    const std::vector<std::uint8_t> stream{
        0xAA,                                                  // junk before the first start code
        0,    0, 0, 1,    0x09, 0xF0,                          // AUD
        0,    0, 0, 1,    0x67, 0x42, 0xC0, 0x1E, 0xDA,        // SPS
        0,    0, 1, 0x68, 0xCE, 0x3C, 0x80,                    // PPS
        0,    0, 1, 0x65, 0x88, 0x84, 0x00, 0x00, 0x03, 0x01,  // IDR slice with an escape
    };
    const auto units = nal_units(stream);
    REQUIRE(units.size() == 4);
    CHECK(units[0].type == static_cast<std::uint8_t>(NalType::aud));
    CHECK(units[0].bytes.size() == 2);
    CHECK(units[1].type == static_cast<std::uint8_t>(NalType::sps));
    CHECK(units[1].bytes.size() == 5);
    CHECK(units[2].type == static_cast<std::uint8_t>(NalType::pps));
    CHECK(units[2].bytes.size() == 4);
    CHECK(units[3].type == static_cast<std::uint8_t>(NalType::idr_slice));
    CHECK(units[3].bytes.size() == 7);  // 00 00 03 is an escape, not a start code
    CHECK(avc_codec_string(stream) == "avc1.42C01E");
}

TEST_CASE("annex b: nothing to find", "[sim_video][annex_b]") {
    CHECK(nal_units({}).empty());
    const std::vector<std::uint8_t> no_code{1, 2, 3, 0, 0, 2};
    CHECK(nal_units(no_code).empty());
    const std::vector<std::uint8_t> no_sps{0, 0, 1, 0x09, 0xF0, 0, 0, 1, 0x67, 0x42};
    CHECK(nal_units(no_sps).size() == 2);
    CHECK_FALSE(avc_codec_string(no_sps));  // an SPS too short to hold its level
}
