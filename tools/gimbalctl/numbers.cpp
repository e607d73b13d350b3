#include "numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

namespace gimbalctl {
namespace {

bool is_integer_syntax(std::string_view text) {
    if (!text.empty() && text.front() == '-') text.remove_prefix(1);
    if (text.empty()) return false;
    for (char c : text) {
        if (c < '0' || c > '9') return false;
    }
    return true;
}

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    for (;;) {
        const auto at = text.find(separator);
        parts.push_back(text.substr(0, at));
        if (at == std::string_view::npos) return parts;
        text.remove_prefix(at + 1);
    }
}

}  // namespace

std::optional<Json> parse_number(std::string_view text) {
    // from_chars does not take a leading '+', people do type it.
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return std::nullopt;
    const char* first = text.data();
    const char* last = text.data() + text.size();

    if (is_integer_syntax(text)) {
        std::int64_t integer = 0;
        const auto [end, ec] = std::from_chars(first, last, integer);
        if (ec == std::errc{} && end == last) return Json(integer);
        // Too large for 64 bits: fall through and send it as a double.
    }
    double real = 0.0;
    const auto [end, ec] = std::from_chars(first, last, real);
    if (ec != std::errc{} || end != last || !std::isfinite(real)) return std::nullopt;
    return Json(real);
}

std::optional<Json> parse_point(std::string_view text) {
    const auto parts = split(text, ',');
    if (parts.size() != 2 && parts.size() != 3) return std::nullopt;
    const auto lat = parse_number(parts[0]);
    const auto lon = parse_number(parts[1]);
    if (!lat || !lon) return std::nullopt;
    if (parts.size() == 2) return Json{{"lat", *lat}, {"lon", *lon}};  // alt: the terrain's
    const auto alt = parse_number(parts[2]);
    if (!alt) return std::nullopt;
    return Json{{"lat", *lat}, {"lon", *lon}, {"alt", *alt}};
}

CLI::Validator number_check() {
    return CLI::Validator(
        [](const std::string& text) {
            return parse_number(text) ? std::string{} : "'" + text + "' is not a number";
        },
        "");
}

CLI::Validator positive_check() {
    return CLI::Validator(
        [](const std::string& text) {
            const auto n = parse_number(text);
            return n && n->get<double>() > 0 ? std::string{}
                                             : "'" + text + "' is not a number above 0";
        },
        "");
}

CLI::Validator count_check() {
    return CLI::Validator(
        [](const std::string& text) {
            const auto n = parse_number(text);
            return n && n->is_number_integer() && n->get<double>() >= 1
                       ? std::string{}
                       : "'" + text + "' is not a whole number of at least 1";
        },
        "");
}

CLI::Validator point_check() {
    return CLI::Validator(
        [](const std::string& text) {
            return parse_point(text)
                       ? std::string{}
                       : "'" + text + "' is not a point LAT,LON[,ALT] (e.g. 45.7,-121.5,300)";
        },
        "");
}

Json number_json(const std::string& text) {
    auto number = parse_number(text);
    if (!number) throw CLI::ConversionError("'" + text + "' is not a number");
    return *number;
}

}  // namespace gimbalctl
