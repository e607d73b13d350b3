// Numbers typed on the command line become JSON numbers of the same kind: "300" is sent as
// the integer 300 and "45.7" as a double, so the daemon sees exactly what the user wrote.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "json_types.hpp"

namespace gimbalctl {

// A finite decimal number (integer, fraction or exponent form); nullopt if it is not one.
std::optional<Json> parse_number(std::string_view text);

// A path point "LAT,LON,ALT" -> {"lat":..,"lon":..,"alt":..}, or "LAT,LON" without "alt"
// (the daemon's terrain gives it); nullopt if malformed.
std::optional<Json> parse_point(std::string_view text);

// CLI11 checks that reject what the parsers above reject, so bad input is a usage error.
CLI::Validator number_check();
CLI::Validator point_check();
// A number above 0 (--timeout); CLI11's PositiveNumber would print the whole double range.
CLI::Validator positive_check();
// A whole number of at least 1 (--count).
CLI::Validator count_check();

// Converts text that passed number_check() (throws CLI::ConversionError otherwise).
Json number_json(const std::string& text);

}  // namespace gimbalctl
