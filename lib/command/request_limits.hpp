// The limits every request meets before anything parses it (contract section 14), on every
// transport: at most 8192 bytes, JSON nested at most 32 deep. Checked on the raw text, so
// an oversize or deeply nested request costs one linear scan and no allocation: nlohmann's
// parser keeps a stack per level, and its dump() recurses once per level.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "command/result.hpp"

namespace gimbal::command {

inline constexpr std::size_t max_request_bytes = 8192;
inline constexpr std::size_t max_json_depth = 32;

// True when `text`, read as JSON, opens more than `max_depth` arrays or objects inside one
// another. Brackets inside strings do not count; whether the text is valid JSON at all is
// left to the parser.
bool nested_deeper_than(std::string_view text, std::size_t max_depth);

// too_large (over max_request_bytes) or bad_json (nested deeper than max_json_depth), else
// nullopt. The message names the limit, never the request's content.
std::optional<Error> check_request_limits(std::string_view text);

}  // namespace gimbal::command
