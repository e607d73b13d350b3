#include "calendar/utc.hpp"

#include <cmath>
#include <cstdio>

namespace gimbal::calendar {

namespace {

bool is_leap(int y) {
    return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

int days_in_month(int y, int m) {
    static constexpr int days[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && is_leap(y) ? 29 : days[m - 1];
}

// Reads exactly `digits` decimal digits at s[at..].
std::optional<int> digits_at(std::string_view s, std::size_t at, std::size_t digits) {
    if (s.size() < at + digits) return std::nullopt;
    int v = 0;
    for (std::size_t k = at; k < at + digits; ++k) {
        if (s[k] < '0' || s[k] > '9') return std::nullopt;
        v = v * 10 + (s[k] - '0');
    }
    return v;
}

}  // namespace

std::string to_iso8601(const DateTime& t) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%04u-%02u-%02uT%02u:%02u:%02uZ", unsigned{t.year},
                  unsigned{t.month}, unsigned{t.day}, unsigned{t.hour}, unsigned{t.minute},
                  unsigned{t.second});
    return buf;
}

std::optional<DateTime> parse_iso8601(std::string_view s) {
    // YYYY-MM-DDTHH:MM:SS
    if (s.size() < 19 || s[4] != '-' || s[7] != '-' || (s[10] != 'T' && s[10] != 't') ||
        s[13] != ':' || s[16] != ':')
        return std::nullopt;
    const auto y = digits_at(s, 0, 4), mo = digits_at(s, 5, 2), d = digits_at(s, 8, 2),
               h = digits_at(s, 11, 2), mi = digits_at(s, 14, 2), se = digits_at(s, 17, 2);
    if (!y || !mo || !d || !h || !mi || !se) return std::nullopt;
    if (*mo < 1 || *mo > 12 || *d < 1 || *d > days_in_month(*y, *mo) || *h > 23 || *mi > 59 ||
        *se > 60)
        return std::nullopt;
    std::size_t i = 19;
    if (i < s.size() && s[i] == '.') {
        ++i;
        const std::size_t first = i;
        while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
        if (i == first) return std::nullopt;
    }
    const std::string_view zone = s.substr(i);
    if (zone != "Z" && zone != "z" && zone != "+00:00") return std::nullopt;
    return DateTime{static_cast<std::uint16_t>(*y), static_cast<std::uint8_t>(*mo),
                    static_cast<std::uint8_t>(*d),  static_cast<std::uint8_t>(*h),
                    static_cast<std::uint8_t>(*mi), static_cast<std::uint8_t>(*se)};
}

DateTime from_unix_seconds(double unix_s) {
    // Howard Hinnant's civil_from_days.
    const auto secs = static_cast<long long>(std::floor(unix_s));
    long long days = secs / 86400;
    long long rem = secs % 86400;
    if (rem < 0) {
        rem += 86400;
        --days;
    }
    days += 719468;
    const long long era = (days >= 0 ? days : days - 146096) / 146097;
    const long long doe = days - era * 146097;
    const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    long long y = yoe + era * 400;
    const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const long long mp = (5 * doy + 2) / 153;
    const long long d = doy - (153 * mp + 2) / 5 + 1;
    const long long m = mp < 10 ? mp + 3 : mp - 9;
    if (m <= 2) ++y;
    return DateTime{static_cast<std::uint16_t>(y),
                    static_cast<std::uint8_t>(m),
                    static_cast<std::uint8_t>(d),
                    static_cast<std::uint8_t>(rem / 3600),
                    static_cast<std::uint8_t>(rem / 60 % 60),
                    static_cast<std::uint8_t>(rem % 60)};
}

double to_unix_seconds(const DateTime& t) {
    // Howard Hinnant's days_from_civil.
    const long long y = static_cast<long long>(t.year) - (t.month <= 2 ? 1 : 0);
    const long long m = t.month;
    const long long era = (y >= 0 ? y : y - 399) / 400;
    const long long yoe = y - era * 400;
    const long long doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + t.day - 1;
    const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    const long long days = era * 146097 + doe - 719468;
    return static_cast<double>(days * 86400 + t.hour * 3600LL + t.minute * 60LL + t.second);
}

}  // namespace gimbal::calendar
