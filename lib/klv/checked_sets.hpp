// The UAS Datalink sets of one KLV unit (a PES payload, a metadata access unit) as a reader
// of untrusted bytes takes them (contract section 14 v4): found, each checked before it is
// expanded (size, checksum, item count: decode()), the good ones decoded and their JSON made
// to fit a size limit - so what a hostile stream can make a reader keep and show is bounded
// by the limits, not by the stream. Pure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "klv/ber.hpp"

namespace gimbal::klv {

// A good set: its bytes as they came (key through checksum) and its decoded JSON, cut to
// the limit by fit_json().
struct CheckedSet {
    Bytes bytes;
    nlohmann::json json;
    bool truncated = false;  // fit_json() left items out
};

struct CheckedSets {
    std::vector<CheckedSet> sets;  // good sets in order, at most max_sets
    std::uint64_t bad_checksums = 0;
    std::uint64_t refused = 0;  // too large, malformed, or past max_sets
};

struct CheckLimits {
    std::size_t max_json_bytes = 8 * 1024;  // each set's JSON, written compact
    std::size_t max_sets = 64;              // good sets taken from one unit
};

CheckedSets check_sets(std::span<const std::uint8_t> unit, const CheckLimits& limits = {});

// Makes a decoded set's JSON fit `max_bytes` when written compact (dump()): the "unknown"
// and "invalid" groups are left out first, then the largest remaining items one at a time,
// and "truncated": true is added. Small items - positions, angles, times - stay. Returns
// whether anything was left out.
bool fit_json(nlohmann::json& decoded, std::size_t max_bytes);

}  // namespace gimbal::klv
