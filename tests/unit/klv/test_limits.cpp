// The limits of a reader of untrusted KLV (contract section 14 v4): a set over 64 KiB or with
// more than 1024 items is refused before it is decoded, the checksum is checked before any
// item is read, check_sets() takes at most max_sets good sets from a unit, and fit_json()
// makes a decoded set's JSON fit its limit, leaving out the unknown tags first.
#include <catch2/catch.hpp>

#include "klv/checked_sets.hpp"
#include "klv/checksum.hpp"
#include "klv/local_set.hpp"
#include "klv_test_util.hpp"

using namespace gimbal::klv;
using nlohmann::json;

namespace {

// A set of `items` copies of one raw item (tag, value), a time stamp first, the checksum
// right (or wrong) last. Built by hand: encode() would refuse nothing here, but this shows
// the exact bytes.
Bytes raw_set(std::size_t items, std::uint32_t tag, const Bytes& value, bool good_sum = true) {
    Bytes body = {0x02, 0x08, 0x00, 0x04, 0x60, 0x50, 0x58, 0x4E, 0x01, 0x80};
    for (std::size_t i = 0; i < items; ++i) {
        append_ber_oid(body, tag);
        append_ber_length(body, value.size());
        body.insert(body.end(), value.begin(), value.end());
    }
    Bytes set(uas_datalink_key.begin(), uas_datalink_key.end());
    append_ber_length(set, body.size() + 4);
    set.insert(set.end(), body.begin(), body.end());
    set.push_back(0x01);
    set.push_back(0x02);
    const std::uint16_t sum = checksum16(set) ^ (good_sum ? 0 : 0x5A5A);
    set.push_back(static_cast<std::uint8_t>(sum >> 8));
    set.push_back(static_cast<std::uint8_t>(sum & 0xFF));
    return set;
}

}  // namespace

TEST_CASE("KLV limits: a set over 64 KiB is refused from its length alone") {
    // 13,000 unknown 3-byte items: about 66 KB, within what a UDP datagram's PES could carry.
    const Bytes big = raw_set(13'000, 200, {0xAB, 0xCD, 0xEF});
    REQUIRE(big.size() > max_set_bytes);
    const DecodeResult r = decode(big);
    CHECK(r.status == DecodeStatus::too_large);
    CHECK(r.items.empty());
    CHECK(r.json.empty());
    CHECK(r.consumed == big.size());
    // Only the key and the length are needed to refuse it: the rest need not even be there.
    const DecodeResult head = decode(std::span(big).first(20));
    CHECK(head.status == DecodeStatus::too_large);
    CHECK(head.consumed == 0);
    // Under 64 KiB a set of large items is decoded.
    const Bytes small = raw_set(100, 200, Bytes(600, 0x11));
    REQUIRE(small.size() <= max_set_bytes);
    CHECK(decode(small).ok());
}

TEST_CASE("KLV limits: more than 1024 items is refused before it is decoded") {
    const Bytes at_limit = raw_set(max_set_items - 2, 200, {0x01});  // + time stamp + checksum
    const DecodeResult ok = decode(at_limit);
    REQUIRE(ok.ok());
    CHECK(ok.items.size() == max_set_items);
    const Bytes over = raw_set(max_set_items - 1, 200, {0x01});
    REQUIRE(over.size() <= max_set_bytes);
    const DecodeResult r = decode(over);
    CHECK(r.status == DecodeStatus::too_large);
    CHECK(r.reason == "more than 1024 items");
    CHECK(r.items.empty());
    CHECK(r.json.empty());
}

TEST_CASE("KLV limits: the checksum is checked before anything is decoded") {
    // 10,000 zero-length unknown items with a wrong checksum: refused, nothing read.
    const Bytes bad = raw_set(10'000, 300, {}, false);
    const DecodeResult r = decode(bad);
    CHECK(r.status == DecodeStatus::bad_checksum);
    CHECK(r.items.empty());
    CHECK(r.json.empty());
    CHECK(r.checksum_computed != r.checksum_stored);
    // The same with its checksum right is refused for its item count instead.
    CHECK(decode(raw_set(10'000, 300, {})).status == DecodeStatus::too_large);
}

TEST_CASE("KLV limits: check_sets takes good sets up to max_sets and counts the rest") {
    Bytes unit;
    const Bytes good = raw_set(3, 13, {0x55, 0x95, 0xB6, 0x6D});
    const Bytes bad = raw_set(3, 13, {0x55, 0x95, 0xB6, 0x6D}, false);
    unit.insert(unit.end(), bad.begin(), bad.end());
    for (int i = 0; i < 5; ++i) unit.insert(unit.end(), good.begin(), good.end());
    const Bytes huge = raw_set(13'000, 200, {0xAB, 0xCD, 0xEF});
    unit.insert(unit.end(), huge.begin(), huge.end());
    CheckLimits limits;
    limits.max_sets = 3;
    const CheckedSets c = check_sets(unit, limits);
    CHECK(c.sets.size() == 3);
    CHECK(c.refused == 2 + 1);  // past max_sets (not even looked at): two good, the huge one
    CHECK(c.bad_checksums == 1);
    for (const auto& s : c.sets) {
        CHECK(s.bytes == good);
        CHECK(s.json["sensor_latitude"].is_number());
        CHECK_FALSE(s.truncated);
    }
}

TEST_CASE("KLV limits: fit_json leaves out unknown tags first, then the largest items") {
    // A valid 46 KB set of mostly unknown tags (the review's STATE of 165 KB), with a position.
    LocalSet set;
    set.add(tag_of("precision_time_stamp"), std::uint64_t{1'700'000'000'000'000});
    set.add(tag_of("sensor_latitude"), 45.5);
    set.add(tag_of("sensor_longitude"), -121.25);
    set.add(tag_of("mission_id"), std::string(100, 'M'));
    set.add(tag_of("platform_tail_number"), std::string(120, 'T'));
    for (std::uint32_t tag = 200; tag < 200 + 900; ++tag) set.add(tag, Bytes(48, 0xEE));
    const Encoded e = encode(set);
    REQUIRE(e.ok());
    REQUIRE(e.value().size() > 40'000);
    const DecodeResult r = decode(e.value());
    REQUIRE(r.ok());
    REQUIRE(r.json.dump().size() > 80'000);

    json fitted = r.json;
    CHECK(fit_json(fitted, 8192));
    CHECK(fitted.dump().size() <= 8192);
    CHECK(fitted["truncated"] == true);
    CHECK_FALSE(fitted.contains("unknown"));
    CHECK(fitted["sensor_latitude"] == 45.5);
    CHECK(fitted["sensor_longitude"] == -121.25);
    CHECK(fitted["mission_id"] == std::string(100, 'M'));

    // A tight limit: the largest known items go next, the small ones stay.
    json tight = r.json;
    CHECK(fit_json(tight, 160));
    CHECK(tight.dump().size() <= 160);
    CHECK(tight["sensor_latitude"] == 45.5);
    CHECK_FALSE(tight.contains("platform_tail_number"));

    // A set that fits is left as it is.
    json same = r.json;
    CHECK_FALSE(fit_json(same, same.dump().size()));
    CHECK(same == r.json);
}
