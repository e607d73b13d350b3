// Every per-item example value that MISB ST 0601 publishes (section 8, "Example Value" and
// "Example LS Packet" of each item), encoded and decoded. Sources, as cited per row:
//   ST 0601.14a - the edition's own example blocks (section 8.N);
//   ST 0601.11  - section 8 "Conversions and Mappings of Metadata Types";
//   ST 0601.16+ - items added or re-exemplified in later editions (section 8.N).
// Items without a usable published example are listed at the end with the reason.
#include <catch2/catch.hpp>
#include <cmath>

#include "klv/mapping.hpp"
#include "klv_test_util.hpp"

using namespace gimbal::klv;
using klv_test::decoded;
using klv_test::encoded_hex;

namespace {

struct NumberExample {
    std::uint32_t tag;
    double value;  // JSON units
    const char* hex;
    const char* source;
};

// Numbers: the example value must encode to the example bytes, and the bytes must decode to
// the value within half a mapping step (the standard prints values at full precision, or
// rounded to the item's resolution).
const NumberExample number_examples[] = {
    {5, 159.974365, "71C2", "ST 0601.14a 8.5: 159.974365 deg -> 0x71C2"},
    {6, -0.431531724, "FD3D", "ST 0601.14a 8.6: -0.431531724 deg -> 0xFD3D"},
    {7, 3.40586566, "08B8", "ST 0601.14a 8.7: 3.40586566 deg -> 0x08B8"},
    {8, 147, "93", "ST 0601.11 8: true airspeed 147 m/s -> 0x93"},
    {9, 159, "9F", "ST 0601.11 8: indicated airspeed 159 m/s -> 0x9F"},
    {13, 60.176822966978335, "5595B66D", "ST 0601.14a 8.13: 60.176822966978335 deg -> 0x5595B66D"},
    {14, 128.42675904204452, "5B5360C4", "ST 0601.14a 8.14: 128.42675904204452 deg -> 0x5B5360C4"},
    {15, 14190.7195, "C221", "ST 0601.14a 8.15: 14190.7195 m -> 0xC221"},
    {16, 144.571298, "CD9C", "ST 0601.14a 8.16: 144.571298 deg -> 0xCD9C"},
    {17, 152.643626, "D917", "ST 0601.14a 8.17: 152.643626 deg -> 0xD917"},
    {18, 160.71921143697557, "724A0A20", "ST 0601.14a 8.18: 160.71921143697557 deg -> 0x724A0A20"},
    {19, -168.79232483394085, "87F84B86",
     "ST 0601.14a 8.19: -168.79232483394085 deg -> 0x87F84B86"},
    {20, 176.86543764939194, "7DC55ECE", "ST 0601.14a 8.20: 176.86543764939194 deg -> 0x7DC55ECE"},
    {21, 68590.983298744770, "03830926", "ST 0601.14a 8.21: 68590.98329874477 m -> 0x03830926"},
    {22, 722.819867, "1281", "ST 0601.14a 8.22: 722.819867 m -> 0x1281"},
    {23, -10.542388633146132, "F101A229",
     "ST 0601.14a 8.23: -10.542388633146132 deg -> 0xF101A229"},
    {24, 29.157890122923014, "14BC082B", "ST 0601.14a 8.24: 29.157890122923014 deg -> 0x14BC082B"},
    {25, 3216.03723, "34F3", "ST 0601.14a 8.25: 3216.03723 m -> 0x34F3"},
    // Offsets: the example's corner minus the example frame centre (-10.5423886331461,
    // 29.157890122923).
    {26, -10.579637999887 + 10.5423886331461, "C06E",
     "ST 0601.11 8: corner 1 lat -10.579637999887 -> 0xC06E"},
    {27, 29.1273677986333 - 29.157890122923, "CBE9",
     "ST 0601.11 8: corner 1 lon 29.1273677986333 -> 0xCBE9"},
    {28, -10.5661816260963 + 10.5423886331461, "D765",
     "ST 0601.11 8: corner 2 lat -10.5661816260963 -> 0xD765"},
    {29, 29.140824172424 - 29.157890122923, "E2E0",
     "ST 0601.11 8: corner 2 lon 29.140824172424 -> 0xE2E0"},
    {30, -10.5527275411938 + 10.5423886331461, "EE5B",
     "ST 0601.11 8: corner 3 lat -10.5527275411938 -> 0xEE5B"},
    {31, 29.1542782573265 - 29.157890122923, "F9D6",
     "ST 0601.11 8: corner 3 lon 29.1542782573265 -> 0xF9D6"},
    {32, -10.5392711674031 + 10.5423886331461, "0552",
     "ST 0601.11 8: corner 4 lat -10.5392711674031 -> 0x0552"},
    {33, 29.1677346311172 - 29.157890122923, "10CD",
     "ST 0601.11 8: corner 4 lon 29.1677346311172 -> 0x10CD"},
    {35, 235.924, "A7C4", "ST 0601.11 8: wind direction 235.924 deg -> 0xA7C4"},
    {36, 69.80392, "B2", "ST 0601.11 8: wind speed 69.80392 m/s -> 0xB2"},
    {37, 3725.185, "BEBA", "ST 0601.11 8: static pressure 3725.185 mbar -> 0xBEBA"},
    {38, 14818.68, "CA35", "ST 0601.11 8: density altitude 14818.68 m -> 0xCA35"},
    {39, 84, "54", "ST 0601.11 8: outside air temperature 84 C -> 0x54"},
    {40, -79.163850051892850, "8F695262", "ST 0601.14a 8.40: -79.16385005189285 deg -> 0x8F695262"},
    {41, 166.40081296041646, "765457F2", "ST 0601.14a 8.41: 166.40081296041646 deg -> 0x765457F2"},
    {42, 18389.0471, "F823", "ST 0601.14a 8.42: 18389.0471 m -> 0xF823"},
    {43, 6, "03", "ST 0601.11 8: target track gate width 6 px -> 0x03"},
    {44, 30, "0F", "ST 0601.11 8: target track gate height 30 px -> 0x0F"},
    {49, 1191.958, "3D07", "ST 0601.11 8: differential pressure 1191.958 mbar -> 0x3D07"},
    {50, -8.670177, "C883", "ST 0601.11 8: angle of attack -8.670177 deg -> 0xC883"},
    {51, -61.88693, "D3FE", "ST 0601.11 8: vertical speed -61.88693 m/s -> 0xD3FE"},
    {52, -5.082475, "DF79", "ST 0601.11 8: sideslip angle -5.082475 deg -> 0xDF79"},
    {53, 2088.96, "6AF4", "ST 0601.11 8: airfield barometric pressure 2088.96 mbar -> 0x6AF4"},
    {54, 8306.806, "7670", "ST 0601.11 8: airfield elevation 8306.806 m -> 0x7670"},
    {55, 50.58823, "81", "ST 0601.11 8: relative humidity 50.58823 % -> 0x81"},
    {56, 140, "8C", "ST 0601.14a 8.56: 140 m/s -> 0x8C"},
    {57, 3506979.0316063400, "B38EACF1", "ST 0601.14a 8.57: 3506979.03160634 m -> 0xB38EACF1"},
    {58, 6420.539, "A45D", "ST 0601.11 8: fuel remaining 6420.539 kg -> 0xA45D"},
    {62, 1743, "06CF", "ST 0601.16+ 8.62: laser PRF code 1743 -> 0x06CF"},
    {64, 311.8682, "DDC5", "ST 0601.11 8: magnetic heading 311.8682 deg -> 0xDDC5"},
    {65, 13, "0D", "ST 0601.14a 8.65: version 13 -> 0x0D"},
    {67, -86.041207348947, "85A15A39",
     "ST 0601.11 8: alternate platform latitude -86.041207348947 -> 0x85A15A39"},
    {68, 0.155527554524842, "001C501C",
     "ST 0601.11 8: alternate platform longitude 0.155527554524842 -> 0x001C501C"},
    {69, 9.445334, "0BB3", "ST 0601.11 8: alternate platform altitude 9.445334 m -> 0x0BB3"},
    {71, 32.60242, "172F", "ST 0601.11 8: alternate platform heading 32.60242 deg -> 0x172F"},
    {75, 14190.7195, "C221", "ST 0601.14a 8.75: sensor ellipsoid height 14190.7195 m -> 0xC221"},
    {76, 9.445334, "0BB3",
     "ST 0601.11 8: alternate platform ellipsoid height 9.445334 m -> 0x0BB3"},
    {78, 9.445334, "0BB3",
     "ST 0601.11 8: frame centre height above ellipsoid 9.445334 m -> 0x0BB3"},
    {82, -10.579637999887, "F0F41244",
     "ST 0601.11 8: corner latitude point 1 (full) -> 0xF0F41244"},
    {83, 29.1273677986333, "14B679B9",
     "ST 0601.11 8: corner longitude point 1 (full) -> 0x14B679B9"},
    {84, -10.5661816260963, "F0F8F87E",
     "ST 0601.11 8: corner latitude point 2 (full) -> 0xF0F8F87E"},
    {85, 29.140824172424, "14B8ECD6",
     "ST 0601.11 8: corner longitude point 2 (full) -> 0x14B8ECD6"},
    {86, -10.5527275411938, "F0FDDE81",
     "ST 0601.11 8: corner latitude point 3 (full) -> 0xF0FDDE81"},
    {87, 29.1542782573265, "14BB5FD8",
     "ST 0601.11 8: corner longitude point 3 (full) -> 0x14BB5FD8"},
    {88, -10.5392711674031, "F102C4BB",
     "ST 0601.11 8: corner latitude point 4 (full) -> 0xF102C4BB"},
    {89, 29.1677346311172, "14BDD2F5",
     "ST 0601.11 8: corner longitude point 4 (full) -> 0x14BDD2F5"},
    {91, 3.405814, "04D804DF",
     "ST 0601.11 8: platform roll angle (full) 3.405814 deg -> 0x04D804DF"},
    {92, -8.670177, "F3AB48EF", "ST 0601.11 8: angle of attack (full) -8.670177 deg -> 0xF3AB48EF"},
    {96, 13898.5463, "00D92A", "ST 0601.14a 8.96: target width extended 13898.5463 m -> 0x00D92A"},
    {103, 23456.24, "2F921E",
     "ST 0601.14a 8.103: density altitude extended 23456.24 m -> 0x2F921E"},
    {104, 23456.24, "2F921E", "ST 0601.14a 8.104: sensor ellipsoid height extended -> 0x2F921E"},
    {105, 23456.24, "2F921E",
     "ST 0601.14a 8.105: alternate platform ellipsoid height ext. -> 0x2F921E"},
    {109, 1625.0, "0001A0", "ST 0601.14a 8.109: range to recovery location 1.625 km -> 0x0001A0"},
    {112, 125.0, "1F40", "ST 0601.14a 8.112: platform course angle 125 deg -> 0x1F40"},
    {113, 2150.0, "05F500", "ST 0601.14a 8.113: altitude above ground level 2150 m -> 0x05F500"},
    {114, 2154.5, "05F740", "ST 0601.14a 8.114: radar altimeter 2154.5 m -> 0x05F740"},
    {117, 1.0, "3E90", "ST 0601.14a 8.117: sensor azimuth rate 1 deg/s -> 0x3E90 (2 bytes)"},
    {118, 0.004176, "3E8011",
     "ST 0601.14a 8.118: sensor elevation rate 0.004176 deg/s -> 0x3E8011"},
    {119, -50.0, "3B60", "ST 0601.14a 8.119: sensor roll rate -50 deg/s -> 0x3B60 (2 bytes)"},
    {120, 72.0, "4800", "ST 0601.14a 8.120: storage percent full 72 % -> 0x4800"},
    {123, 7, "07", "ST 0601.16+ 8.123: 7 navigation satellites -> 0x07"},
    {132, 2400.0, "0257C0", "ST 0601.14a 8.132: transmission frequency 2400 MHz -> 0x0257C0"},
    {134, 55.0, "3700", "ST 0601.14a 8.134: zoom percentage 55 % -> 0x3700"},
    {136, 30, "1E", "ST 0601.14a 8.136: leap seconds 30 s -> 0x1E"},
    {137, 5025.678901, "012B8DC635",
     "ST 0601.14a 8.137: correction offset 1:23:45.678901 -> 0x012B8DC635"},
};

}  // namespace

TEST_CASE("ST 0601 published examples: numbers encode to the example bytes and back") {
    for (const auto& ex : number_examples) {
        INFO(ex.source);
        const std::string hex = ex.hex;
        const auto length = static_cast<std::uint8_t>(hex.size() / 2);
        const TagSpec& row = *find_tag(ex.tag);
        // Variable-length items are written at the example's length.
        const std::uint8_t asked = row.max_length != 0 ? length : 0;
        CHECK(encoded_hex(ex.tag, ex.value, asked) == hex);
        const nlohmann::json back = decoded(ex.tag, hex);
        REQUIRE(back.is_number());
        // IMAPB truncates: its value can lie up to one step above the decoded one.
        const double steps = row.kind == Kind::imapb ? 1.0 : 0.5;
        const double tolerance = std::max(step(ex.tag, length) * steps, 1e-9);
        CHECK(std::abs(back.get<double>() - ex.value) <= tolerance);
    }
}

TEST_CASE("ST 0601 published examples: strings") {
    const struct {
        std::uint32_t tag;
        const char* text;
        const char* hex;
        const char* source;
    } examples[] = {
        {3, "MISSION01", "4D495353494F4E3031", "ST 0601.9 8: mission ID MISSION01"},
        {4, "AF-101", "41462D313031", "ST 0601.9 8: platform tail number AF-101"},
        {10, "MQ1-B", "4D51312D42", "ST 0601.11 8: platform designation MQ1-B"},
        {11, "EO", "454F", "ST 0601.14a 8.11: image source sensor EO"},
        {12, "Geodetic WGS84", "47656F6465746963205747533834", "ST 0601.14a 8.12"},
        {59, "TOP GUN", "544F502047554E", "ST 0601.11 8: platform call sign TOP GUN"},
        {70, "APACHE", "415041434845", "ST 0601.11 8: alternate platform name APACHE"},
    };
    for (const auto& ex : examples) {
        INFO(ex.source);
        CHECK(encoded_hex(ex.tag, std::string(ex.text)) == ex.hex);
        CHECK(decoded(ex.tag, ex.hex) == ex.text);
    }
}

TEST_CASE("ST 0601 published examples: time stamps") {
    // ST 0601.14a 8.2: "Oct. 24, 2008. 00:13:29.913" -> 0x000459F4A6AA4AA8.
    CHECK(encoded_hex(2, std::uint64_t{1224807209913000}) == "000459F4A6AA4AA8");
    CHECK(decoded(2, "000459F4A6AA4AA8") == "2008-10-24T00:13:29.913000Z");
    // ST 0601.11 8: event start time 0x0002D5CF4DDC9A35. The example's printed text
    // ("April 16, 1995. 13:44:54") is an hour off and drops the microseconds; the bytes are
    // 798036294670901 us since 1970.
    CHECK(encoded_hex(72, std::uint64_t{798036294670901}) == "0002D5CF4DDC9A35");
    CHECK(decoded(72, "0002D5CF4DDC9A35") == "1995-04-16T12:44:54.670901Z");
}

TEST_CASE("ST 0601 published examples: flags, enumerations, nibbles and lists") {
    // ST 0601.11 8: generic flag data 0x31 = laser on, slant range measured, image invalid.
    CHECK(encoded_hex(47, std::uint64_t{0x31}) == "31");
    CHECK(decoded(47, "31") == nlohmann::json{{"laser_range", true},
                                              {"auto_track", false},
                                              {"ir_polarity", false},
                                              {"icing_status", false},
                                              {"slant_range", true},
                                              {"image_invalid", true}});
    // ST 0601.11 8: weapon load 0xAFD8 = station 10, substation 15, type 13, variant 8.
    CHECK(encoded_hex(60, std::uint64_t{0xAFD8}) == "AFD8");
    CHECK(decoded(60, "AFD8") == nlohmann::json{{"station_number", 10},
                                                {"substation_number", 15},
                                                {"weapon_type", 13},
                                                {"weapon_variant", 8}});
    // ST 0601.11 8: weapon fired 0xBA = station 11, substation 10.
    CHECK(decoded(61, "BA") == nlohmann::json{{"station_number", 11}, {"substation_number", 10}});
    // ST 0601.11 8: operational mode 0x00 = "Other".
    CHECK(encoded_hex(77, std::string("other")) == "00");
    CHECK(decoded(77, "00") == "other");
    // ST 0601.16+ 8.116: control command verification list 0x0307 = commands 3 and 7.
    CHECK(encoded_hex(116, std::vector<std::uint64_t>{3, 7}) == "0307");
    CHECK(decoded(116, "0307") == nlohmann::json::array({3, 7}));
    // ST 0601.16+ 8.121: active wavelength list 0x0103 = wavelengths 1 and 3.
    CHECK(encoded_hex(121, std::vector<std::uint64_t>{1, 3}) == "0103");
    CHECK(decoded(121, "0103") == nlohmann::json::array({1, 3}));
    // ST 0601.16+ 8.124: positioning method source 0x03 = on-board INS and GPS.
    CHECK(decoded(124, "03") == nlohmann::json{{"on_board_ins", true},
                                               {"gps", true},
                                               {"galileo", false},
                                               {"qzss", false},
                                               {"navic", false},
                                               {"glonass", false},
                                               {"beidou_1", false},
                                               {"beidou_2", false}});
    // ST 0601.16+ 8.139: active payloads 0x0B = payloads 0, 1 and 3.
    CHECK(encoded_hex(139, std::vector<std::uint64_t>{0, 1, 3}) == "0B");
    CHECK(decoded(139, "0B") == nlohmann::json::array({0, 1, 3}));
}

// Published examples left out, and why:
//  34 icing detected (0x9B), 63 sensor field of view name (0xD1): ST 0601.11 prints values
//     outside the item's own enumeration; decoded here as their numbers (see below).
//  79, 80 sensor north/east velocity: ST 0601.11 prints -327 m/s as 0x8000 and 0x0000, which
//     are the reserved value and zero under the item's own map.
//  45, 46 target error estimate CE90/LE90: ST 0601.11 prints 425.319 m -> 0x1A95 and
//     609.0718 m -> 0x2611, i.e. 16 steps a metre; the item's map (0..2^16-1 onto 0..4095 m)
//     gives 0x1A97 and 0x2613. The map is normative; the bytes decode to 425.2152 m and
//     608.9231 m (below).
//  90 platform pitch angle (full): ST 0601.11 prints 3 bytes for a 4-byte item.
//  93 platform sideslip angle (full): ST 0601.11 prints no value.
//  Nested sets and packs (48, 73, 74, 81, 94, 95, 97-102, 115, 122, 128, 130, 138, 140-143)
//  are kept as hex and have no mapping to check.
TEST_CASE("ST 0601 published examples outside their enumerations decode as numbers") {
    CHECK(decoded(34, "9B") == 155);
    CHECK(decoded(63, "D1") == 209);
    CHECK(decoded(34, "02") == "icing_detected");
    CHECK(decoded(45, "1A95").get<double>() == Approx(425.2152).margin(1e-4));
    CHECK(decoded(46, "2611").get<double>() == Approx(608.9231).margin(1e-4));
    CHECK(decoded(63, "08") == "continuous_zoom");
}
