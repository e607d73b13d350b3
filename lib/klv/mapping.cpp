#include "klv/mapping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gimbal::klv {

namespace {

double unsigned_top(const TagSpec& row) {
    return std::ldexp(1.0, 8 * row.length) - 1.0;
}
double signed_top(const TagSpec& row) {
    return std::ldexp(1.0, 8 * row.length - 1) - 1.0;
}

}  // namespace

std::int64_t linear_to_wire(const TagSpec& row, double x) {
    if (row.is_signed) {
        const double top = signed_top(row);
        const auto reserved = static_cast<std::int64_t>(-top) - 1;
        if (std::isnan(x) || x < row.min || x > row.max) {
            if (row.reserved) return reserved;
            if (std::isnan(x)) return 0;
        }
        const double w = std::round(top / row.max * std::clamp(x, row.min, row.max));
        return static_cast<std::int64_t>(std::clamp(w, -top, top));
    }
    const double top = unsigned_top(row);
    if (std::isnan(x)) return 0;
    const double w =
        std::round(top / (row.max - row.min) * (std::clamp(x, row.min, row.max) - row.min));
    return static_cast<std::int64_t>(std::clamp(w, 0.0, top));
}

std::optional<double> linear_from_wire(const TagSpec& row, std::int64_t wire) {
    if (row.is_signed) {
        const double top = signed_top(row);
        if (static_cast<double>(wire) < -top) {
            if (row.reserved) return std::nullopt;
            return row.min;
        }
        return row.max / top * static_cast<double>(wire);
    }
    return (row.max - row.min) / unsigned_top(row) * static_cast<double>(wire) + row.min;
}

Imapb imapb_of(const TagSpec& row, int length) {
    return {row.min, row.max, length > 0 ? length : row.length};
}

bool in_range(std::uint32_t tag, double x) {
    const TagSpec* row = find_tag(tag);
    if (row == nullptr || std::isnan(x)) return false;
    if (row->kind != Kind::linear && row->kind != Kind::imapb) return false;
    const double wire = x / row->to_json;
    return wire >= row->min && wire <= row->max;
}

double step(std::uint32_t tag, int length) {
    const TagSpec* row = find_tag(tag);
    if (row == nullptr) return 0;
    if (row->kind == Kind::linear)
        return (row->max - row->min) /
               (row->is_signed ? 2 * signed_top(*row) : unsigned_top(*row)) * row->to_json;
    if (row->kind == Kind::imapb) return imapb_of(*row, length).step() * row->to_json;
    return 0;
}

bool corner_offset_fits(double corner_deg, double center_deg) {
    const double offset = corner_deg - center_deg;
    return std::isfinite(offset) && std::abs(offset) <= 0.075;
}

std::string iso8601_utc(std::uint64_t microseconds) {
    const std::uint64_t seconds = microseconds / 1000000;
    const auto micros = static_cast<unsigned>(microseconds % 1000000);
    const auto days = static_cast<std::int64_t>(seconds / 86400);
    const auto day_seconds = static_cast<unsigned>(seconds % 86400);
    // Civil date from days since 1970-01-01 (the proleptic Gregorian era arithmetic of
    // Howard Hinnant's civil_from_days).
    const std::int64_t z = days + 719468;
    const std::int64_t era = z / 146097;
    const auto doe = static_cast<unsigned>(z - era * 146097);
    const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    const unsigned mp = (5 * doy + 2) / 153;
    const unsigned day = doy - (153 * mp + 2) / 5 + 1;
    const unsigned month = mp < 10 ? mp + 3 : mp - 9;
    const std::int64_t year = static_cast<std::int64_t>(yoe) + era * 400 + (month <= 2 ? 1 : 0);
    char text[48];
    std::snprintf(text, sizeof text, "%04lld-%02u-%02uT%02u:%02u:%02u.%06uZ",
                  static_cast<long long>(year), month, day, day_seconds / 3600,
                  day_seconds / 60 % 60, day_seconds % 60, micros);
    return text;
}

}  // namespace gimbal::klv
