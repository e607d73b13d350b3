// Whole local sets: the published example packets with their checksums, a round trip of every
// tag at its range ends, reserved values, truncated and over-long input, bad checksums,
// find_sets over joined and split buffers, and the encoder's refusals.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "klv/checksum.hpp"
#include "klv/mapping.hpp"
#include "klv_test_util.hpp"

using namespace gimbal::klv;
using klv_test::from_hex;
using klv_test::to_hex;
using nlohmann::json;

namespace {

// MISB ST 0902.5 (the MISB Minimum Subset of ST 0601) example packets: "dynamic only" and
// "dynamic and constant" metadata, as the standard prints them.
const Bytes st0902_dynamic_only = from_hex(
    "060E2B34020B01010E01030101000000 61"
    "0208 0004605058 4E0180 0502 71C2 0602 FD3D 0702 08B8 0D04 5595B66D 0E04 5B5360C4"
    "0F02 C221 1002 CD9C 1102 D917 1204 724A0A20 1304 87F84B86 1404 00000000"
    "1504 03830926 1602 1281 1704 F101A229 1804 14BC082B 1902 34F3 4101 06 0102 C850");
const Bytes st0902_dynamic_and_constant = from_hex(
    "060E2B34020B01010E01030101000000 81D2"
    "0208 00046050584E0180 030A 4D697373696F6E203132 0502 71C2 0602 FD3D 0702 08B8"
    "0A08 5072656461746F72 0B07 454F204E6F7365 0C0E 47656F6465746963205747533834"
    "0D04 5595B66D 0E04 5B5360C4 0F02 C221 1002 CD9C 1102 D917 1204 724A0A20 1304 87F84B86"
    "1404 7DC55ECE 1504 03830926 1602 1281 1704 F101A229 1804 14BC082B 1902 34F3"
    "301C 0101 01 0201 07 0305 2F2F555341 0C01 07 0D06 00550053 0041 1602 000A"
    "4101 06 5E22 0170F592F02373364AF8AA9162C00F2EB2DA16B74341000841A0BE365B5AB96A3645"
    "0102 AA43");

LocalSet with_time(std::uint32_t tag, Value value, std::uint8_t length = 0) {
    LocalSet set;
    set.add(2, std::uint64_t{1224807209913000});
    set.add(tag, std::move(value), length);
    return set;
}

json round_trip(const LocalSet& set) {
    const Encoded e = encode(set);
    INFO((e ? "" : e.error().message));
    REQUIRE(e.ok());
    const DecodeResult r = decode(e.value(), Digits::exact);
    INFO(r.reason);
    REQUIRE(r.ok());
    CHECK(r.consumed == e.value().size());
    return r.json;
}

}  // namespace

TEST_CASE("ST 0902.5 dynamic-only example: checksum 0xC850 and every value") {
    const DecodeResult r = decode(st0902_dynamic_only);
    INFO(r.reason);
    REQUIRE(r.ok());
    CHECK(r.checksum_stored == 0xC850);
    CHECK(r.checksum_computed == 0xC850);
    CHECK(r.consumed == st0902_dynamic_only.size());
    CHECK(r.items.size() == 19);
    CHECK(r.items.front().tag == 2);
    CHECK(r.items.back().tag == 1);
    const json& j = r.json;
    CHECK(j["precision_time_stamp"] == "2009-01-12T22:08:22.000000Z");
    CHECK(j["platform_heading_angle"].get<double>() == Approx(159.9744).margin(0.003));
    CHECK(j["sensor_latitude"].get<double>() == Approx(60.176822967).margin(1e-8));
    CHECK(j["sensor_longitude"].get<double>() == Approx(128.426759042).margin(1e-8));
    CHECK(j["sensor_true_altitude"].get<double>() == Approx(14190.72).margin(0.2));
    CHECK(j["sensor_relative_roll_angle"] == 0);
    CHECK(j["frame_center_elevation"].get<double>() == Approx(3216.037).margin(0.2));
    CHECK(j["uas_datalink_ls_version_number"] == 6);
    CHECK(j["checksum"] == 0xC850);
    CHECK_FALSE(j.contains("unknown"));
    CHECK_FALSE(j.contains("invalid"));

    // Re-encoding the decoded values in the same order gives the same bytes.
    const DecodeResult exact = decode(st0902_dynamic_only, Digits::exact);
    LocalSet set;
    for (const RawItem& item : exact.items) {
        const TagSpec& row = *find_tag(item.tag);
        if (item.tag == 1) continue;
        const json& v = exact.json[std::string(row.name)];
        if (item.tag == 2)
            set.add(2, std::uint64_t{0x00046050584E0180});
        else
            set.add(item.tag, v.get<double>());
    }
    const Encoded e = encode(set);
    REQUIRE(e.ok());
    CHECK(to_hex(e.value()) == to_hex(st0902_dynamic_only));
}

TEST_CASE("ST 0902.5 dynamic-and-constant example: printed checksum wrong, values readable") {
    // The standard prints 0xAA43 for this packet; the running sum of its bytes is 0x3E1E (and
    // its CRC-16-CCITT is not 0xAA43 either), so a decoder counts it as a bad checksum - and
    // decodes nothing of it. The dynamic-only example above, whose sum matches, shows the
    // algorithm is the right one.
    const DecodeResult bad = decode(st0902_dynamic_and_constant);
    CHECK(bad.status == DecodeStatus::bad_checksum);
    CHECK(bad.checksum_stored == 0xAA43);
    CHECK(bad.checksum_computed == 0x3E1E);
    CHECK(bad.consumed == st0902_dynamic_and_constant.size());
    CHECK(bad.items.empty());
    CHECK(bad.json.empty());
    // With the sum written in, its values read as the standard lists them.
    Bytes fixed = st0902_dynamic_and_constant;
    fixed[fixed.size() - 2] = 0x3E;
    fixed[fixed.size() - 1] = 0x1E;
    const DecodeResult r = decode(fixed);
    REQUIRE(r.ok());
    CHECK(r.json["mission_id"] == "Mission 12");
    CHECK(r.json["platform_designation"] == "Predator");
    CHECK(r.json["image_source_sensor"] == "EO Nose");
    CHECK(r.json["image_coordinate_system"] == "Geodetic WGS84");
    CHECK(r.json["security_local_set"] ==
          "01010102010703052F2F5553410C01070D060055005300411602000A");
    CHECK(r.json["miis_core_identifier"].get<std::string>().size() == 2 * 0x22);
    CHECK(r.json["uas_datalink_ls_version_number"] == 6);
}

TEST_CASE("Checksum: running 16-bit sum over key through the checksum's length byte") {
    // The word sum of "060E 2B34 0200 81BB" (ST 0601's own checksum illustration) is 0xB4FD.
    CHECK(checksum16(from_hex("060E2B34020081BB")) == 0xB4FD);
    // An odd byte count sums as if a zero byte followed.
    CHECK(checksum16(from_hex("0102 03")) == 0x0402);
    CHECK(checksum16(Bytes{}) == 0);
}

TEST_CASE("Every tag round-trips at the ends of its range and in between") {
    for (const TagSpec& row : st0601_tags) {
        INFO("tag " << row.tag << " " << row.name);
        const std::string name(row.name);
        switch (row.kind) {
            case Kind::checksum:
                break;
            case Kind::linear:
            case Kind::imapb: {
                const double lo = row.min * row.to_json;
                const double hi = row.max * row.to_json;
                for (const double x : {lo, hi, lo + (hi - lo) * 0.3183}) {
                    const json j = round_trip(with_time(row.tag, x));
                    REQUIRE(j[name].is_number());
                    // IMAPB truncates (up to one step), linear maps round (half a step).
                    const double steps = row.kind == Kind::imapb ? 1.0 : 0.5;
                    CHECK(std::abs(j[name].get<double>() - x) <=
                          step(row.tag) * steps + 1e-9 * std::abs(x));
                }
                break;
            }
            case Kind::time_us: {
                for (const std::uint64_t us : {std::uint64_t{0}, std::uint64_t{1224807209913000},
                                               std::uint64_t{253402300799999999}}) {
                    const json j = round_trip(with_time(row.tag, us));
                    CHECK(j[name] == iso8601_utc(us));
                }
                CHECK(iso8601_utc(253402300799999999) == "9999-12-31T23:59:59.999999Z");
                CHECK(iso8601_utc(0) == "1970-01-01T00:00:00.000000Z");
                break;
            }
            case Kind::uint: {
                const std::size_t n = row.max_length != 0 ? row.max_length : row.length;
                const std::uint64_t top = n >= 8 ? ~0ull : (1ull << (8 * n)) - 1;
                for (const std::uint64_t v : {std::uint64_t{0}, top / 3, top})
                    CHECK(round_trip(with_time(row.tag, v))[name] == v);
                break;
            }
            case Kind::sint: {
                const std::size_t n = row.max_length != 0 ? row.max_length : row.length;
                const std::int64_t top = n >= 8 ? std::numeric_limits<std::int64_t>::max()
                                                : (std::int64_t{1} << (8 * n - 1)) - 1;
                for (const std::int64_t v : {-top - 1, std::int64_t{-7}, std::int64_t{0}, top}) {
                    const json j =
                        round_trip(with_time(row.tag, static_cast<double>(v) * row.to_json));
                    CHECK(j[name].get<double>() == Approx(static_cast<double>(v) * row.to_json));
                }
                break;
            }
            case Kind::string: {
                for (const std::string& s :
                     {std::string("A"), std::string("EO Nose"), std::string(127, 'z')})
                    CHECK(round_trip(with_time(row.tag, s))[name] == s);
                break;
            }
            case Kind::enumeration: {
                const auto last = static_cast<std::uint64_t>(row.names.size() - 1);
                CHECK(round_trip(with_time(row.tag, std::uint64_t{0}))[name] == row.names.front());
                CHECK(round_trip(with_time(row.tag, last))[name] == row.names.back());
                CHECK(round_trip(with_time(row.tag, std::string(row.names[1])))[name] ==
                      row.names[1]);
                break;
            }
            case Kind::flags: {
                const json none = round_trip(with_time(row.tag, std::uint64_t{0}))[name];
                const json all = round_trip(with_time(row.tag, std::uint64_t{0xFF}))[name];
                for (const auto label : row.names) {
                    CHECK(none[std::string(label)] == false);
                    CHECK(all[std::string(label)] == true);
                }
                break;
            }
            case Kind::nibbles: {
                const std::uint64_t top = (1ull << (8 * row.length)) - 1;
                const json zero = round_trip(with_time(row.tag, std::uint64_t{0}))[name];
                const json full = round_trip(with_time(row.tag, top))[name];
                for (const auto label : row.names) {
                    CHECK(zero[std::string(label)] == 0);
                    CHECK(full[std::string(label)] == 15);
                }
                break;
            }
            case Kind::oid_list: {
                const std::vector<std::uint64_t> ids{0, 127, 128, 16384, 1ull << 63};
                CHECK(round_trip(with_time(row.tag, ids))[name] == json(ids));
                break;
            }
            case Kind::frame_rate: {
                CHECK(round_trip(with_time(row.tag, std::vector<std::uint64_t>{30}))[name] ==
                      json{{"numerator", 30}, {"denominator", 1}});
                CHECK(
                    round_trip(with_time(row.tag, std::vector<std::uint64_t>{60000, 1001}))[name] ==
                    json{{"numerator", 60000}, {"denominator", 1001}});
                break;
            }
            case Kind::bit_list: {
                const std::vector<std::uint64_t> ids{0, 9, 1015};
                CHECK(round_trip(with_time(row.tag, ids))[name] == json(ids));
                break;
            }
            case Kind::raw: {
                const Bytes nested{0x01, 0x01, 0x01, 0x02, 0x01, 0x07};
                const json j = round_trip(with_time(row.tag, nested));
                if (row.multiple)
                    CHECK(j[name] == json::array({"010101020107"}));
                else
                    CHECK(j[name] == "010101020107");
                break;
            }
        }
    }
}

TEST_CASE("Tags above 127 are written as two-byte BER-OIDs") {
    const Encoded e = encode(with_time(143, Bytes{0xAB}));
    REQUIRE(e.ok());
    const std::string hex = to_hex(e.value());
    CHECK(hex.find("810F01AB") != std::string::npos);
    CHECK(decode(e.value()).json["metadata_substream_id_pack"] == "AB");
}

TEST_CASE("Encoder: order kept, checksum last, long-form set length") {
    LocalSet set;
    set.add(2, std::uint64_t{1224807209913000});
    set.add(1, std::uint64_t{0});  // ignored: the checksum is computed
    set.add(3, std::string(120, 'M'));
    set.add(65, std::uint64_t{st0601_version});
    const Encoded e = encode(set);
    REQUIRE(e.ok());
    CHECK(e.value()[16] == 0x81);  // the value is 10 + 122 + 3 + 4 = 139 bytes
    CHECK(e.value()[17] == 139);
    const DecodeResult r = decode(e.value());
    REQUIRE(r.ok());
    REQUIRE(r.items.size() == 4);
    CHECK(r.items[0].tag == 2);
    CHECK(r.items[1].tag == 3);
    CHECK(r.items[2].tag == 65);
    CHECK(r.items[3].tag == 1);
}

TEST_CASE("Reserved values: out of range and error decode to null") {
    // ST 0601: 0x8000 / 0x80000000 on the signed maps.
    CHECK(klv_test::encoded_hex(6, Reserved{}) == "8000");
    CHECK(klv_test::encoded_hex(6, 25.0) == "8000");  // pitch beyond +-20 deg: "out of range"
    CHECK(klv_test::encoded_hex(6, std::nan("")) == "8000");
    CHECK(klv_test::encoded_hex(13, Reserved{}) == "80000000");
    CHECK(klv_test::encoded_hex(26, 0.2) == "8000");  // corner offset beyond +-0.075 deg
    CHECK(klv_test::decoded(6, "8000").is_null());
    CHECK(klv_test::decoded(13, "80000000").is_null());
    CHECK(klv_test::decoded(79, "8000").is_null());
    // The map's own ends are not reserved.
    CHECK(klv_test::encoded_hex(6, -20.0) == "8001");
    CHECK(klv_test::encoded_hex(6, 20.0) == "7FFF");
    CHECK(klv_test::encoded_hex(13, -90.0) == "80000001");
    // IMAPB special values (top bit set) decode to null too.
    CHECK(klv_test::decoded(112, "C800").is_null());
    // A zero-length item means "unknown" (ST 0601 6.5).
    CHECK(klv_test::decoded(13, "").is_null());
    CHECK(klv_test::decoded(3, "").is_null());
}

TEST_CASE("Unsigned maps without a reserved value saturate; NaN is refused") {
    CHECK(klv_test::encoded_hex(15, 25000.0) == "FFFF");  // 19000 m
    CHECK(klv_test::encoded_hex(15, -2000.0) == "0000");  // -900 m
    CHECK(klv_test::encoded_hex(5, 360.0) == "FFFF");
    CHECK(klv_test::encoded_hex(96, 2e6) == klv_test::encoded_hex(96, 1.5e6));
    std::string error;
    CHECK(klv_test::encoded_hex(15, std::nan(""), 0, &error).empty());
    CHECK(error.find("NaN") != std::string::npos);
    CHECK(klv_test::encoded_hex(15, Reserved{}, 0, &error).empty());
    CHECK(in_range(15, 19000.0));
    CHECK_FALSE(in_range(15, 19000.5));
    CHECK_FALSE(in_range(3, 1.0));
    CHECK(corner_offset_fits(10.07, 10.0));
    CHECK_FALSE(corner_offset_fits(10.08, 10.0));
}

TEST_CASE("Rounding: half away from zero on linear maps, truncation on IMAPB") {
    // Tag 8 maps 1 m/s per step: 146.5 rounds up, -0.5 m/s saturates at 0.
    CHECK(klv_test::encoded_hex(8, 146.5) == "93");
    CHECK(klv_test::encoded_hex(8, 146.49) == "92");
    // Tag 51 vertical speed: +-180 m/s on +-32767; a value exactly half a step from zero.
    const double half = 180.0 / 32767.0 / 2.0;
    CHECK(klv_test::encoded_hex(51, half * 1.0000001) == "0001");
    CHECK(klv_test::encoded_hex(51, -half * 1.0000001) == "FFFF");
    // ST 1201: floor, so 23456.24 m is 0x2F921E and not ...1F (0.7 of a step above).
    CHECK(klv_test::encoded_hex(103, 23456.24) == "2F921E");
}

TEST_CASE("JSON numbers carry the fewest digits that give the same wire value") {
    const DecodeResult r = decode(st0902_dynamic_only);
    REQUIRE(r.ok());
    for (const auto& [key, value] : r.json.items()) {
        const TagSpec* row = find_tag(key);
        if (row == nullptr || row->kind != Kind::linear || value.is_null()) continue;
        INFO(key << " = " << value.dump());
        const std::string text = value.dump();
        const auto dot = text.find('.');
        const std::size_t decimals = dot == std::string::npos ? 0 : text.size() - dot - 1;
        CHECK(decimals <= 9);
        CHECK(linear_to_wire(*row, value.get<double>()) ==
              linear_to_wire(*row, r.json[key].get<double>()));
    }
    CHECK(r.json["sensor_latitude"].dump() == "60.17682297");
}

TEST_CASE("Malformed input: truncated at every byte, wrong key, over-long length") {
    const Bytes& set = st0902_dynamic_only;
    for (std::size_t n = 0; n < set.size(); ++n) {
        const DecodeResult r = decode(std::span(set).first(n));
        INFO("prefix " << n);
        CHECK(r.status == DecodeStatus::malformed);
        CHECK(r.consumed == 0);
    }
    Bytes wrong_key = set;
    wrong_key[9] = 0x02;
    CHECK(decode(wrong_key).reason == "not the UAS Datalink LS key");
    Bytes indefinite = set;
    indefinite[16] = 0x80;
    CHECK(decode(indefinite).reason == "invalid BER length");
    Bytes nine = set;
    nine[16] = 0x89;
    CHECK(decode(nine).status == DecodeStatus::malformed);
    Bytes too_long = set;
    too_long[16] = 0x62;  // one more value byte than the buffer holds
    CHECK(decode(too_long).reason.rfind("truncated", 0) == 0);
}

TEST_CASE("Malformed input: items past the set, no checksum last") {
    // An item whose length runs past the set's value (which ends with a checksum that
    // matches: items are read only once the checksum is right).
    Bytes past = from_hex("060E2B34020B01010E01030101000000 0A 0D 09 5595B66D 0102");
    const std::uint16_t sum = checksum16(past);
    past.push_back(static_cast<std::uint8_t>(sum >> 8));
    past.push_back(static_cast<std::uint8_t>(sum & 0xFF));
    CHECK(decode(past).reason == "tag 13 runs past the set");
    // Without a checksum that fits, the same bytes are refused before any item is read.
    Bytes no_sum = from_hex("060E2B34020B01010E01030101000000 06 0D 09 5595B66D 0102");
    CHECK(decode(no_sum).reason == "no checksum (tag 1, 2 bytes) as the last item");
    // A set whose last item is not the checksum.
    LocalSet set = with_time(13, 60.0);
    Bytes bytes = encode(set).value();
    bytes.resize(bytes.size() - 4);
    bytes[16] = static_cast<std::uint8_t>(bytes[16] - 4);
    CHECK(decode(bytes).reason == "no checksum (tag 1, 2 bytes) as the last item");
    // A tag whose BER-OID is cut by the end of the set.
    Bytes cut_tag = from_hex("060E2B34020B01010E01030101000000 01 81");
    CHECK(decode(cut_tag).status == DecodeStatus::malformed);
    // Trailing bytes after a set are not read.
    Bytes trailing = st0902_dynamic_only;
    trailing.insert(trailing.end(), {0xDE, 0xAD});
    const DecodeResult r = decode(trailing);
    CHECK(r.ok());
    CHECK(r.consumed == st0902_dynamic_only.size());
}

TEST_CASE("Bad checksum: counted, nothing decoded") {
    for (std::size_t at = 0; at < st0902_dynamic_only.size(); ++at) {
        if (at == 16) continue;  // the set's length: malformed, not a bad checksum
        Bytes bad = st0902_dynamic_only;
        bad[at] ^= 0x01;
        const DecodeResult r = decode(bad);
        INFO("byte " << at);
        const std::size_t trailer = st0902_dynamic_only.size() - 4;  // the checksum's 01 02
        if (at < 16 || at == trailer || at == trailer + 1) {
            CHECK(r.status == DecodeStatus::malformed);
        } else {  // any flipped bit changes the sum: refused before an item is read
            CHECK(r.status == DecodeStatus::bad_checksum);
            CHECK(r.consumed == st0902_dynamic_only.size());
            CHECK(r.items.empty());
        }
    }
    Bytes bad = st0902_dynamic_only;
    bad[bad.size() - 1] ^= 0xFF;
    const DecodeResult r = decode(bad);
    CHECK(r.status == DecodeStatus::bad_checksum);
    CHECK(r.reason == "checksum 0xC8AF, computed 0xC850");
    CHECK(r.json.empty());
    CHECK(r.items.empty());
}

TEST_CASE("Unknown tags and items of the wrong length are kept as hex") {
    LocalSet set = with_time(13, 60.0);
    set.add(200, Bytes{0xAB, 0xCD});
    set.add(14, Bytes{});  // a zero-length item: "unknown" in ST 0601
    Encoded e = encode(set);
    REQUIRE(e.ok());
    DecodeResult r = decode(e.value());
    REQUIRE(r.ok());
    CHECK(r.json["unknown"] == json{{"200", "ABCD"}});
    CHECK(r.json["sensor_longitude"].is_null());
    // A three-byte latitude.
    const Bytes odd = from_hex("060E2B34020B01010E01030101000000 09 0D03 5595B6 0102");
    Bytes fixed = odd;
    const std::uint16_t sum = checksum16(std::span(fixed).first(fixed.size() - 2 + 2));
    fixed.push_back(static_cast<std::uint8_t>(sum >> 8));
    fixed.push_back(static_cast<std::uint8_t>(sum));
    fixed[16] = 0x09;
    r = decode(fixed);
    INFO(r.reason);
    REQUIRE(r.ok());
    CHECK(r.json["invalid"] == json{{"13", "5595B6"}});
    CHECK_FALSE(r.json.contains("sensor_latitude"));
    // Strings are cut at the first zero byte; bytes that are not UTF-8 become '?'.
    CHECK(klv_test::decoded(3, "4142004344") == "AB");
    CHECK(klv_test::decoded(3, "41FF42C3A9") == "A?B\xC3\xA9");
}

TEST_CASE("Encoder refusals name the tag and the reason") {
    const auto error_of = [](LocalSet set) { return encode(set).error().message; };
    CHECK(error_of(with_time(13, std::string("north"))) ==
          "tag 13 (sensor_latitude) takes a number");
    CHECK(error_of(with_time(3, 1.0)) == "tag 3 (mission_id) takes a string");
    CHECK(error_of(with_time(3, std::string(128, 'x'))) ==
          "tag 3 (mission_id) is 128 bytes, at most 127");
    CHECK(error_of(with_time(126, std::string("panning"))) ==
          "tag 126 (sensor_control_mode) has no value named \"panning\"");
    CHECK(error_of(with_time(126, std::uint64_t{7})) ==
          "tag 126 (sensor_control_mode) 7 is past 6");
    CHECK(error_of(with_time(126, std::int64_t{-1})) ==
          "tag 126 (sensor_control_mode) -1 is negative");
    CHECK(error_of(with_time(200, 1.0)) ==
          "tag 200 is not an ST 0601 tag: only raw bytes can be sent");
    CHECK(error_of(with_time(48, std::string("x"))) ==
          "tag 48 (security_local_set) takes raw bytes (a nested set or pack)");
    CHECK(error_of(with_time(112, 1.0, 9)) ==
          "tag 112 (platform_course_angle) IMAPB length must be 1..8");
    CHECK(error_of(with_time(110, std::uint64_t{1} << 40)) ==
          "tag 110 (time_airborne) needs 6 bytes, allowed 1..4");
    CHECK(encode(with_time(110, std::uint64_t{5}, 2)).ok());  // a wider length on request
    CHECK(klv_test::encoded_hex(110, std::uint64_t{5}, 2) == "0005");
}

TEST_CASE("find_sets: several sets, junk between, a set cut at the end") {
    const Bytes a = st0902_dynamic_only;
    const Bytes b = encode(with_time(13, 1.5)).value();
    Bytes buffer{0x00, 0x06, 0x0E, 0xFF};  // junk, including a false start of the key
    buffer.insert(buffer.end(), a.begin(), a.end());
    buffer.insert(buffer.end(), {0x06, 0x0E, 0x2B, 0x34, 0x02, 0x0B, 0x01, 0x01, 0x0E, 0x01, 0x03,
                                 0x01, 0x01, 0x00, 0x00, 0x00, 0x80});  // invalid length
    buffer.insert(buffer.end(), b.begin(), b.end());
    const std::size_t tail_at = buffer.size();
    buffer.insert(buffer.end(), a.begin(), a.begin() + 30);
    const FoundSets found = find_sets(buffer);
    REQUIRE(found.sets.size() == 2);
    CHECK(found.sets[0].offset == 4);
    CHECK(found.sets[0].size == a.size());
    CHECK(found.sets[1].offset == 4 + a.size() + 17);
    CHECK(found.sets[1].size == b.size());
    CHECK(found.keep_from == tail_at);
    for (const SetSpan s : found.sets)
        CHECK(decode(std::span(buffer).subspan(s.offset, s.size)).ok());

    // A key cut by the end of the buffer is kept too; nothing pending keeps nothing.
    Bytes key_start = a;
    key_start.insert(key_start.end(), a.begin(), a.begin() + 5);
    CHECK(find_sets(key_start).keep_from == a.size());
    CHECK(find_sets(a).keep_from == a.size());
    CHECK(find_sets(Bytes{}).sets.empty());
}

TEST_CASE("find_sets: a stream split at every byte offset loses no set") {
    Bytes stream;
    for (int i = 0; i < 3; ++i) {
        const Bytes one = encode(with_time(13, 10.0 * i)).value();
        stream.insert(stream.end(), one.begin(), one.end());
        stream.push_back(0x55);  // junk between sets
    }
    for (std::size_t split = 0; split <= stream.size(); ++split) {
        INFO("split at " << split);
        Bytes pending(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(split));
        std::size_t sets = 0;
        FoundSets f = find_sets(pending);
        sets += f.sets.size();
        pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(f.keep_from));
        pending.insert(pending.end(), stream.begin() + static_cast<std::ptrdiff_t>(split),
                       stream.end());
        f = find_sets(pending);
        sets += f.sets.size();
        CHECK(sets == 3);
    }
}

TEST_CASE("add_corners: offsets while every corner is within 0.075 deg, else full points") {
    const LatLon center{47.40, 8.54};
    LocalSet near;
    CHECK(add_corners(near, center,
                      {{{47.43, 8.50}, {47.43, 8.58}, {47.37, 8.58}, {47.37, 8.50}}}) == 26);
    REQUIRE(near.items.size() == 8);
    CHECK(near.items[0].tag == 26);
    CHECK(std::get<double>(near.items[0].value) == Approx(0.03));
    CHECK(near.items[7].tag == 33);
    CHECK(std::get<double>(near.items[7].value) == Approx(-0.04));
    LocalSet far;
    CHECK(add_corners(far, center,
                      {{{47.43, 8.50}, {47.43, 8.62}, {47.37, 8.58}, {47.37, 8.50}}}) == 82);
    REQUIRE(far.items.size() == 8);
    CHECK(far.items[3].tag == 85);
    CHECK(std::get<double>(far.items[3].value) == 8.62);
    // Decoded offsets come back as offsets: the reader adds the frame centre.
    near.items.insert(near.items.begin(), {2, std::uint64_t{1}, 0});
    const json j = round_trip(near);
    CHECK(j["offset_corner_latitude_point_1"].get<double>() == Approx(0.03).margin(step(26)));
}
