// MISB ST 0601 UAS Datalink Local Sets: build, encode, find, decode. Pure: bytes in, values
// out; no clock (the caller passes precision_time_stamp), no I/O, no logging.
//
// Building and encoding
//   LocalSet set;
//   set.add(tag_of("precision_time_stamp"), std::uint64_t{us_since_1970});  // tag 2 first
//   set.add(tag_of("sensor_latitude"), 60.176822966978335);                 // degrees
//   set.add(tag_of("sensor_true_altitude"), 14190.72);                      // metres MSL
//   set.add(tag_of("sensor_control_mode"), std::string("auto_tracking"));   // enum by name
//   set.add(tag_of("uas_datalink_ls_version_number"), std::uint64_t{st0601_version});
//   Encoded e = encode(set);   // items in the order added, checksum (tag 1) appended last
//   if (!e.ok()) log(e.error); else send(e.bytes);
// Values are in JSON units (st0601.hpp: degrees, metres, m/s, seconds) as double or integer;
// time stamps (tags 2, 72, 131) as microseconds since 1970; strings as std::string;
// enumerations as their index or name; flags and nibbles as the wire integer; lists
// (116, 121, 127, 139) as std::vector<std::uint64_t>; nested sets and packs as raw Bytes.
// Raw Bytes are accepted for any tag and written as they are (an item relayed from a decoded
// set, an unknown tag); empty Bytes make a zero-length item, which ST 0601 reads as "unknown".
// Reserved{} asks for a signed map's reserved "out of range" value. Rounding, saturation
// and the reserved value on out-of-range input: see mapping.hpp. encode() refuses (error set,
// no bytes) a value of the wrong type for its tag, NaN where the map has no reserved value,
// a string over 127 bytes, an enumeration name or index the tag does not have, a list value
// that does not fit, and an unknown tag number given anything but raw Bytes.
//
// Finding and decoding
//   FoundSets found = find_sets(pes_payload);     // zero or more sets, maybe after junk
//   for (auto s : found.sets) {
//       DecodeResult r = decode(pes_payload.subspan(s.offset, s.size));
//       if (r.status == DecodeStatus::bad_checksum) ++bad_checksums;  // and ignore the set
//       else if (r.ok()) use(r.json);                                 // {"sensor_latitude":..}
//   }
// decode() expects the set at the start of its input and reads no further than the set.
// Untrusted bytes are checked before anything is expanded (contract section 14 v4): first
// the set's size (at most max_set_bytes, from its BER length alone), then its checksum, then
// the item count while the items are read (at most max_set_items); only a set that passes
// all three is decoded into items and JSON.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "klv/ber.hpp"
#include "klv/st0601.hpp"

#include "result/result.hpp"

namespace gimbal::klv {

struct Reserved {};  // the tag's reserved "out of range" / error value

using Value = std::variant<double, std::int64_t, std::uint64_t, std::string, Bytes,
                           std::vector<std::uint64_t>, Reserved>;

struct Item {
    std::uint32_t tag = 0;
    Value value;
    // Variable-length kinds (IMAPB, integers, take_off_time): bytes to write; 0 = the row's
    // default (IMAPB) or the fewest that hold the value (integers).
    std::uint8_t length = 0;
};

// An ordered list of items: encode() writes them in this order, so "tag 2 first" is the
// caller's first add(). A tag 1 item is ignored: the checksum is always computed and last.
struct LocalSet {
    std::vector<Item> items;

    // Defined out of line: inlined into callers that add doubles, GCC 12 -O3 warns falsely
    // (-Wmaybe-uninitialized) about the variant's string alternative.
    LocalSet& add(std::uint32_t tag, Value value, std::uint8_t length = 0);
};

// The image corners (upper left, upper right, lower right, lower left; latitude, longitude in
// degrees) as contract section 17 sends them: offsets from the frame centre (tags 26-33) when
// every corner is within 0.075 degrees of it, else the full corner points (tags 82-89).
// Returns the first tag used (26 or 82).
struct LatLon {
    double lat = 0;
    double lon = 0;
};
std::uint32_t add_corners(LocalSet& set, LatLon frame_center, const std::array<LatLon, 4>& corners);

// The set's bytes (key, BER length, items, checksum), or bad_request naming the item it
// refuses: "tag 13 (sensor_latitude) takes a number".
using Encoded = Result<Bytes>;

Encoded encode(const LocalSet& set);
// One item's value bytes (no tag, no length) appended to `out`, or bad_request saying why
// encode() would refuse it ("takes a number").
Status encode_value(const Item& item, Bytes& out);

// A set is at most this long, key through checksum (contract section 14 v4), and has at most
// this many items: ST 0601 defines 143 tags, and a few of them may repeat.
inline constexpr std::size_t max_set_bytes = 64 * 1024;
inline constexpr std::size_t max_set_items = 1024;

enum class DecodeStatus {
    ok,
    bad_checksum,  // the checksum differs: refused before any item was read (json, items empty)
    malformed,     // not a set, truncated, an item running past the set, no checksum last
    too_large,     // over max_set_bytes or max_set_items: refused before it was decoded
};
std::string_view to_string(DecodeStatus status);

struct RawItem {
    std::uint32_t tag = 0;
    std::size_t offset = 0;  // of the value, from the first byte of the key
    Bytes value;
};

// JSON numbers: the fewest decimals that map back to the same wire integer (contract
// section 1), or the decoded double as it is.
enum class Digits { shortest, exact };

struct DecodeResult {
    DecodeStatus status = DecodeStatus::malformed;
    std::string reason;  // why it is malformed, or "checksum 0x.... != computed 0x...."
    // One object keyed by ST 0601 item names (st0601.hpp), in JSON units. A zero-length item
    // or a reserved / special value is null. Tags ST 0601.19 does not define go under
    // "unknown": {"TAG": "HEX"}; an item whose length its kind cannot have (e.g. a 3-byte
    // latitude) under "invalid": {"TAG": "HEX"}. Items that may repeat (100, 101, 102, 115)
    // are arrays of hex strings.
    nlohmann::json json = nlohmann::json::object();
    std::vector<RawItem> items;  // every item in wire order, the checksum included
    // Bytes the set takes (key through checksum) once its length is known and present,
    // whatever the status; 0 when the input is not a set or ends before the set does.
    // Only an ok set has items and json; checksum_* are filled once the checksum was read.
    std::size_t consumed = 0;
    std::uint16_t checksum_stored = 0;
    std::uint16_t checksum_computed = 0;

    bool ok() const { return status == DecodeStatus::ok; }
};

DecodeResult decode(std::span<const std::uint8_t> bytes, Digits digits = Digits::shortest);

// The JSON value of one item's value bytes under its row (what decode() puts under the
// item's name). `valid` is false when the length does not suit the kind.
nlohmann::json value_json(const TagSpec& row, std::span<const std::uint8_t> value, Digits digits,
                          bool& valid);

struct SetSpan {
    std::size_t offset = 0;
    std::size_t size = 0;
};

struct FoundSets {
    std::vector<SetSpan> sets;  // complete sets in order (checksums not checked)
    // Where an incomplete set (or the start of a key) begins at the end of the input, for a
    // caller that joins buffers; the input's size when there is none.
    std::size_t keep_from = 0;
};

// Every UAS Datalink LS in `bytes`: a KLV PES payload may hold several, or begin with the
// tail of an earlier one. Bytes that are not a key are skipped; a key whose BER length is
// invalid is skipped too.
FoundSets find_sets(std::span<const std::uint8_t> bytes);

}  // namespace gimbal::klv
