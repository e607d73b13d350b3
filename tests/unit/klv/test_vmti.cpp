// lib/klv/vmti: the MISB ST 0903 VMTI local set. The golden bytes are built by hand from the
// standard's tables as jmisb quotes them (vmti.hpp): VMTI LS tags 4 version, 5 total targets,
// 6 reported targets, 8 frame width, 9 frame height, 101 VTarget series; VTarget pack: BER-OID
// target id, tags 1 centroid, 2 top left, 3 bottom right (pixel number = column + (row - 1) *
// frame width), 5 confidence (percent), 17 location (IMAPB lat -90..90 4 bytes, lon -180..180
// 4 bytes, HAE -900..19000 2 bytes).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "klv/vmti.hpp"
#include "klv_test_util.hpp"

using namespace gimbal::klv;
using klv_test::from_hex;
using klv_test::to_hex;

namespace {

// A 1280 x 720 frame with one target, id 7: centroid at row 361, column 641; box from row 301,
// column 581 to row 421, column 701; 87 % confidence; at 47.5 N, 8.25 E, 400 m HAE.
VmtiSet sample_set() {
    VmtiSet s;
    s.version = 5;
    s.total_targets = 1;
    s.reported_targets = 1;
    s.frame_width = 1280;
    s.frame_height = 720;
    VmtiTarget t;
    t.id = 7;
    t.centroid = 461441;      // 641 + 360 * 1280
    t.top_left = 384581;      // 581 + 300 * 1280
    t.bottom_right = 538301;  // 701 + 420 * 1280
    t.confidence_pct = 87;
    t.location = VmtiLocation{47.5, 8.25, 400.0};
    s.targets.push_back(t);
    return s;
}

// clang-format off
const std::string sample_hex =
    "040105"        // tag 4 version: 5
    "050101"        // tag 5 total targets: 1
    "060101"        // tag 6 reported targets: 1
    "08020500"      // tag 8 frame width: 1280
    "090202D0"      // tag 9 frame height: 720
    "6520"          // tag 101 VTarget series, 32 bytes
    "1F"            //   pack length 31
    "07"            //   target id 7 (BER-OID)
    "0103070A81"    //   tag 1 centroid pixel 461441
    "020305DE45"    //   tag 2 top left pixel 384581
    "03030836BD"    //   tag 3 bottom right pixel 538301
    "050157"        //   tag 5 confidence 87
    "110A"          //   tag 17 location, 10 bytes:
    "44C00000"      //     (47.5 + 90) * 2^23
    "2F100000"      //     (8.25 + 180) * 2^22
    "0514";         //     400 + 900 (sF = 1)
// clang-format on

// The offsets at which the sample's top-level items end: a prefix cut there is a smaller
// valid set, one cut anywhere else is truncated.
const std::vector<std::size_t> sample_item_ends = {0, 3, 6, 9, 13, 17};

}  // namespace

TEST_CASE("VMTI pixel numbers count from 1 at the top left, row by row") {
    CHECK(vmti_pixel_number(1, 1, 1280) == 1);
    CHECK(vmti_pixel_number(1, 1280, 1280) == 1280);
    CHECK(vmti_pixel_number(2, 1, 1280) == 1281);
    CHECK(vmti_pixel_number(720, 1280, 1280) == 921600);
    const VmtiRowColumn rc = vmti_row_column(461441, 1280);
    CHECK(rc.row == 361);
    CHECK(rc.column == 641);
    CHECK(vmti_row_column(1280, 1280).row == 1);
    CHECK(vmti_row_column(1280, 1280).column == 1280);
}

TEST_CASE("VMTI encodes the hand-built golden set") {
    const auto bytes = encode_vmti(sample_set());
    REQUIRE(bytes.ok());
    CHECK(to_hex(*bytes) == sample_hex);
}

TEST_CASE("VMTI decodes the hand-built golden set") {
    const auto set = decode_vmti(from_hex(sample_hex));
    REQUIRE(set.ok());
    CHECK(*set == sample_set());
    const nlohmann::json j = vmti_json(*set);
    CHECK(j["version"] == 5);
    CHECK(j["frame_width"] == 1280);
    CHECK(j["frame_height"] == 720);
    REQUIRE(j["targets"].size() == 1);
    const auto& t = j["targets"][0];
    CHECK(t["id"] == 7);
    const nlohmann::json centroid = {{"pixel", 461441}, {"row", 361}, {"column", 641}};
    CHECK(t["centroid"] == centroid);
    CHECK(t["top_left"]["row"] == 301);
    CHECK(t["top_left"]["column"] == 581);
    CHECK(t["bottom_right"]["row"] == 421);
    CHECK(t["bottom_right"]["column"] == 701);
    CHECK(t["confidence_level"] == 87);
    const nlohmann::json location = {{"lat", 47.5}, {"lon", 8.25}, {"hae", 400}};
    CHECK(t["location"] == location);
}

TEST_CASE(
    "VMTI round trips: other items, time stamp, frame number, row and column, 22-byte "
    "location") {
    VmtiSet s = sample_set();
    s.time_us = 1'700'000'000'123'456;
    s.frame_number = 123456;
    s.other.push_back({3, {'S', 'i', 'm'}});  // system name, kept raw
    s.targets[0].centroid_row = 361;
    s.targets[0].centroid_column = 641;
    s.targets[0].other.push_back({4, {0x02}});  // priority, kept raw
    s.targets[0].location = VmtiLocation{-33.8688, 151.2093, 58.0};
    VmtiTarget second;
    second.id = 300;  // a two-byte BER-OID
    s.targets.push_back(second);
    const auto bytes = encode_vmti(s);
    REQUIRE(bytes.ok());
    auto back = decode_vmti(*bytes);
    REQUIRE(back.ok());
    // The location comes back within one IMAPB step.
    const VmtiLocation got = *back->targets[0].location;
    CHECK(std::abs(got.lat_deg - -33.8688) <= std::ldexp(1.0, -23));
    CHECK(std::abs(got.lon_deg - 151.2093) <= std::ldexp(1.0, -22));
    CHECK(got.hae_m == 58.0);
    back->targets[0].location = s.targets[0].location;
    CHECK(*back == s);
    CHECK(vmti_json(*back)["precision_time_stamp"] == "2023-11-14T22:13:20.123456Z");

    // A location with sigmas and correlations (22 bytes) keeps its point.
    const auto with_rhos =
        from_hex("65 1A 19 01 11 16 44C00000 2F100000 0514" + std::string(24, '0'));
    const auto decoded = decode_vmti(with_rhos);
    REQUIRE(decoded.ok());
    CHECK((decoded->targets[0].location == VmtiLocation{47.5, 8.25, 400.0}));
}

TEST_CASE(
    "VMTI: every truncation of a valid set is refused, or is a smaller set at an item "
    "boundary") {
    const auto whole = from_hex(sample_hex);
    for (std::size_t n = 0; n < whole.size(); ++n) {
        INFO("first " << n << " bytes");
        const auto r = decode_vmti(std::span(whole).first(n));
        const bool boundary = std::find(sample_item_ends.begin(), sample_item_ends.end(), n) !=
                              sample_item_ends.end();
        if (boundary) {
            CHECK(r.ok());
        } else {
            REQUIRE_FALSE(r.ok());
            CHECK(r.error().code == gimbal::code::bad_request);
            CHECK(r.error().message.find("truncated") != std::string::npos);
        }
    }
}

TEST_CASE("VMTI refuses bad input with a clear error") {
    const auto refused = [](const std::string& hex) {
        const auto r = decode_vmti(from_hex(hex));
        return r.ok() ? std::string("decoded") : r.error().message;
    };
    CHECK(refused("0800") == "VMTI: set tag 8: 0 bytes, needs 1..3");
    CHECK(refused("080100") == "VMTI: tag 8 is 0");
    CHECK(refused("0804000005 00") == "VMTI: set tag 8: 4 bytes, needs 1..3");
    CHECK(refused("040105 040105") == "VMTI: set tag 4 appears twice");
    CHECK(refused("0880") == "VMTI: set tag 8: invalid BER length");
    CHECK(refused("08 88FFFFFFFFFFFFFFFF") ==
          "VMTI: set tag 8: truncated, needs 18446744073709551615 bytes, 0 left");
    CHECK(refused("8080") == "VMTI: set: invalid tag at byte 0");
    CHECK(refused("0203 000000") == "VMTI: tag 2: 3 bytes, needs 8");
    CHECK(refused("6503 05 0105") == "VMTI: VTarget pack 1: truncated, needs 5 bytes, 2 left");
    CHECK(refused("6504 03 01 0500") == "VMTI: target 1 tag 5: 0 bytes, needs 1..1");
    CHECK(refused("6505 04 01 050165") == "VMTI: target 1 confidence 101 is over 100 %");
    CHECK(refused("6505 04 01 010100") == "VMTI: target 1 tag 1: pixel 0");
    CHECK(refused("6506 05 01 1102 0000") == "VMTI: target 1 tag 17: 2 bytes, needs 10, 16 or 22");
    CHECK(refused("650E 0D 01 110A 80000000 00000000 0000") ==
          "VMTI: target 1 tag 17: an IMAPB special value (not a location)");
    CHECK(refused("650E 0D 01 110A 7FFFFFFF 00000000 0000") ==
          "VMTI: target 1 tag 17: a location out of range");
    CHECK(refused("6502 01 81") == "VMTI: VTarget pack: truncated target id");
    CHECK(refused("6501 00") == "VMTI: VTarget pack: truncated target id");
}

TEST_CASE("VMTI bounds the targets and items it reads") {
    std::string series;
    for (std::size_t i = 0; i < max_vmti_targets; ++i) series += "0101";  // pack: id 1, no items
    const auto at_limit = from_hex("65820200" + series);
    REQUIRE(at_limit.size() == 4 + 2 * max_vmti_targets);
    const auto ok = decode_vmti(at_limit);
    REQUIRE(ok.ok());
    CHECK(ok->targets.size() == max_vmti_targets);
    const auto over = decode_vmti(from_hex("65820202" + series + "0101"));
    REQUIRE_FALSE(over.ok());
    CHECK(over.error().message == "VMTI: more than 256 targets");

    std::string items;
    for (std::size_t i = 0; i <= max_vmti_items; ++i) items += "0300";  // empty tag 3s
    const auto many = decode_vmti(from_hex(items));
    REQUIRE_FALSE(many.ok());
    CHECK(many.error().message == "VMTI: more than 4096 items");
}

TEST_CASE("VMTI encode refuses what it cannot write") {
    const auto refused = [](const VmtiSet& s) {
        const auto r = encode_vmti(s);
        return r.ok() ? std::string("encoded") : r.error().message;
    };
    VmtiSet s = sample_set();
    s.frame_width = 0;
    CHECK(refused(s) == "VMTI: frame width 0 is not in 1..16777215");
    s = sample_set();
    s.targets[0].confidence_pct = 101;
    CHECK(refused(s) == "VMTI: confidence 101 is over 100 %");
    s = sample_set();
    s.targets[0].centroid = 0;
    CHECK(refused(s) == "VMTI: centroid pixel number 0 is not in 1..2^48-1");
    s = sample_set();
    s.targets[0].location->lat_deg = std::nan("");
    CHECK(refused(s) == "VMTI: target 7 has a location that is not a number");
    s = sample_set();
    s.targets.resize(max_vmti_targets + 1);
    CHECK(refused(s) == "VMTI: 257 targets, over the limit of 256");
}

TEST_CASE("VMTI: random bytes never crash, and whatever decodes re-encodes to itself") {
    std::mt19937 rng(903);
    const auto base = from_hex(sample_hex);
    std::size_t decoded = 0;
    for (int i = 0; i < 20000; ++i) {
        Bytes bytes;
        if (i % 2 == 0) {  // the sample with a few bytes changed
            bytes = base;
            for (int k = 0; k < 1 + i % 4; ++k)
                bytes[rng() % bytes.size()] = static_cast<std::uint8_t>(rng());
        } else {
            bytes.resize(rng() % 48);
            for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
        }
        const auto r = decode_vmti(bytes);
        if (!r.ok()) {
            CHECK(r.error().message.rfind("VMTI: ", 0) == 0);
            continue;
        }
        ++decoded;
        (void)vmti_json(*r).dump();
        const auto again = encode_vmti(*r);
        REQUIRE(again.ok());
        const auto back = decode_vmti(*again);
        REQUIRE(back.ok());
        CHECK(*back == *r);
    }
    CHECK(decoded > 100);
}
