// MISB ST 0903 Video Moving Target Indicator (VMTI) Local Set, as ST 0601 carries it in tag 74
// (contract section 20): a typed set with its targets, encode() to the local set's bytes,
// decode() of untrusted bytes, and its JSON. Pure.
//
// Where the numbers come from. The ST 0903 document itself was not in reach; every tag number,
// encoding and range below was checked against the open-source jmisb library, which quotes
// ST 0903.5 in its comments (github.com/WestRidgeSystems/jmisb, api/.../klv/st0903/:
// VmtiMetadataKey.java, VTargetMetadataKey.java, VTargetSeries.java, VTargetPack.java,
// vtarget/TargetCentroid.java, vtarget/TargetConfidenceLevel.java, vtarget/TargetLocation.java,
// FrameWidth.java, ST0903Version.java). docs/video.md says the same.
//
// VMTI LS (tag: value), each item tag, BER length, value, like ST 0601's items:
//   1 checksum (for a standalone set; not written here: tag 74 sits inside an ST 0601 set
//     whose own checksum covers it, and the ST 0903 algorithm was not checked - a tag 1
//     that is read is kept as an unchecked item)
//   2 precision time stamp, uint64 microseconds since 1970
//   4 version of ST 0903, uint 1..2 bytes (this writes 5, the revision jmisb implements)
//   5 total targets detected, 6 targets reported: uint 1..3 bytes
//   7 frame number: uint 1..4 bytes
//   8 frame width, 9 frame height: pixels, uint 1..3 bytes, never zero
//   101 VTarget series: VTarget packs, each preceded by its BER length
// VTarget pack: the target id as a BER-OID, then its own items (tag, BER length, value):
//   1 centroid pixel number, 2 bounding box top left, 3 bottom right: uint 1..6 bytes;
//     pixel number = column + (row - 1) * frame width, row and column counted from 1 at the
//     top left (pixel 1)
//   5 confidence level: uint8 percent, 0..100
//   17 target location: ST 1201 IMAPB latitude (-90, 90, 4 bytes), longitude (-180, 180,
//     4 bytes), height above the WGS84 ellipsoid (-900, 19000, 2 bytes); 10 bytes, or 16 / 22
//     with standard deviations and correlations (read, not kept)
//   19 centroid pixel row, 20 centroid pixel column: uint 1..4 bytes
// Other items (system name 3, source sensor 10, fields of view 11-12, algorithm and ontology
// series 102-103; priority 4, history 6, VMask, VObject, ... in a pack) are kept as raw
// items: shown as hex, written back unchanged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <vector>

#include "klv/ber.hpp"
#include "result/result.hpp"

namespace gimbal::klv {

// The ST 0903 revision this writes (tag 4): 5, the one jmisb implements.
inline constexpr std::uint16_t vmti_version = 5;

// Bounds on untrusted input, besides its size: at most this many targets and items.
inline constexpr std::size_t max_vmti_targets = 256;
inline constexpr std::size_t max_vmti_items = 4096;  // in the set and all its packs together

// An item kept as it came (a tag this does not type).
struct VmtiRawItem {
    std::uint32_t tag = 0;
    Bytes value;
    bool operator==(const VmtiRawItem&) const = default;
};

// A point on the WGS84 ellipsoid (VTarget tag 17, its first 10 bytes).
struct VmtiLocation {
    double lat_deg = 0;
    double lon_deg = 0;
    double hae_m = 0;  // height above the ellipsoid
    bool operator==(const VmtiLocation&) const = default;
};

struct VmtiTarget {
    std::uint64_t id = 0;
    // Pixel numbers (1 = top left; see above).
    std::optional<std::uint64_t> centroid, top_left, bottom_right;
    std::optional<std::uint32_t> centroid_row, centroid_column;  // tags 19, 20 (from 1)
    std::optional<std::uint8_t> confidence_pct;                  // 0..100
    std::optional<VmtiLocation> location;
    std::vector<VmtiRawItem> other;
    bool operator==(const VmtiTarget&) const = default;
};

struct VmtiSet {
    std::optional<std::uint64_t> time_us;  // tag 2
    std::optional<std::uint16_t> version = vmti_version;
    std::optional<std::uint32_t> total_targets, reported_targets;
    std::optional<std::uint32_t> frame_number;
    std::optional<std::uint32_t> frame_width, frame_height;
    std::vector<VmtiTarget> targets;  // tag 101 when not empty
    std::vector<VmtiRawItem> other;
    bool operator==(const VmtiSet&) const = default;
};

// The pixel number of a pixel (row and column counted from 1), and back.
std::uint64_t vmti_pixel_number(std::uint32_t row, std::uint32_t column, std::uint32_t width);
struct VmtiRowColumn {
    std::uint64_t row = 0, column = 0;
};
VmtiRowColumn vmti_row_column(std::uint64_t pixel_number, std::uint32_t width);

// The local set's items (no key: ST 0601 tag 74 holds them as they are). Refuses
// (bad_request) what cannot be written: a zero frame size, a confidence over 100, a pixel
// number of zero or past 6 bytes, a location that is not finite, more than max_vmti_targets.
// Numbers outside a location's range are saturated at its ends (ST 1201 IMAPB).
Result<Bytes> encode_vmti(const VmtiSet& set);

// The local set in `bytes` (all of them), or bad_request saying what is wrong: truncated (an
// item or a pack running past its end), an invalid BER length or tag, a value of a length its
// item cannot have, a zero frame size, a confidence over 100, a duplicated item, more than
// max_vmti_targets targets or max_vmti_items items. Work is linear in the input.
Result<VmtiSet> decode_vmti(std::span<const std::uint8_t> bytes);

// The JSON of a set (docs/video.md "VMTI"): snake_case names; pixel numbers as
// {"pixel", "row", "column"} (row and column only when the frame width is known).
nlohmann::json vmti_json(const VmtiSet& set);

}  // namespace gimbal::klv
