// Date and time in UTC, whole seconds, no time zone: what the Viewpro frames carry and how
// STATE shows the vehicle's clock (vehicle.time).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace gimbal::calendar {

struct DateTime {
    std::uint16_t year = 2000;
    std::uint8_t month = 1, day = 1, hour = 0, minute = 0, second = 0;
    friend bool operator==(const DateTime&, const DateTime&) = default;
};

// "2021-08-07T17:27:58Z" (the wire has no sub-second part).
std::string to_iso8601(const DateTime&);
// Accepts "YYYY-MM-DDTHH:MM:SS" with an optional fraction (dropped) and "Z" or "+00:00".
// nullopt when malformed or a field is out of its calendar range.
std::optional<DateTime> parse_iso8601(std::string_view);
// UTC calendar time of a Unix time in seconds (fraction dropped), and back.
DateTime from_unix_seconds(double unix_s);
double to_unix_seconds(const DateTime&);

}  // namespace gimbal::calendar
