// Value mappings of ST 0601 items (the rows of st0601.hpp) and value helpers for callers that
// build sets from typed values (degrees, metres, m/s, seconds). Pure.
//
// Rounding and range policy of the encoder (and of these helpers):
//  - linear maps round half away from zero (contract section 1); IMAPB truncates, as ST 1201
//    defines it;
//  - a value outside the item's range, or NaN, is written as the item's reserved value when
//    the map has one (the signed maps: 0x8000 / 0x80000000, which ST 0601 names "out of
//    range", "reserved" or "N/A (off-earth)"; decoders show it as null);
//  - otherwise a value outside the range is saturated at the nearest end (ST 0601 has no way
//    to say "more than 19000 m"), and NaN is refused with an error.
// Callers that must not lose a value check in_range() first, e.g. to send the full corner
// points 82-89 instead of the offsets 26-33 (corner_offset_fits()).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "klv/imapb.hpp"
#include "klv/st0601.hpp"

namespace gimbal::klv {

// The wire integer of `x` for a linear row (sign-extended for signed maps).
std::int64_t linear_to_wire(const TagSpec& row, double x);
// The value of a wire integer (already sign-extended for signed maps); std::nullopt for the
// reserved value.
std::optional<double> linear_from_wire(const TagSpec& row, std::int64_t wire);

// The IMAPB parameters of an imapb row at `length` bytes (0: the row's default).
Imapb imapb_of(const TagSpec& row, int length = 0);

// Is `x` (JSON units) inside the range of tag `tag`'s linear or IMAPB map? False for other
// kinds, unknown tags and NaN.
bool in_range(std::uint32_t tag, double x);
// One wire step in JSON units (the resolution) of a linear or IMAPB tag; 0 for other kinds.
double step(std::uint32_t tag, int length = 0);

// Can a corner at `corner_deg` be sent as an offset (tags 26-33) from the frame centre at
// `center_deg`? ST 0601 limits offsets to +-0.075 degrees.
bool corner_offset_fits(double corner_deg, double center_deg);

// Microseconds since 1970-01-01T00:00:00Z as ISO-8601 UTC with microseconds,
// "2008-10-24T00:13:29.913000Z".
std::string iso8601_utc(std::uint64_t microseconds);

}  // namespace gimbal::klv
