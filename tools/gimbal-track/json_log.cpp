#include "json_log.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>

namespace gimbal_track {

namespace {

const char* name(Level level) {
    switch (level) {
        case Level::debug:
            return "debug";
        case Level::info:
            return "info";
        case Level::warn:
            return "warn";
        case Level::error:
            return "error";
    }
    return "info";
}

std::string now_utc() {
    const auto now = std::chrono::system_clock::now();
    const auto us =
        std::chrono::duration_cast<std::chrono::microseconds>(now.time_since_epoch()).count();
    const std::time_t s = static_cast<std::time_t>(us / 1000000);
    std::tm tm{};
    gmtime_r(&s, &tm);
    char text[80];
    std::snprintf(text, sizeof(text), "%04d-%02d-%02dT%02d:%02d:%02d.%06dZ", tm.tm_year + 1900,
                  tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec,
                  static_cast<int>(us % 1000000));
    return text;
}

}  // namespace

std::optional<Level> parse_level(std::string_view n) {
    for (const Level l : {Level::debug, Level::info, Level::warn, Level::error})
        if (n == name(l)) return l;
    return std::nullopt;
}

void Log::write(Level level, std::string_view event, std::string_view msg,
                const nlohmann::json& fields) const {
    if (level < level_) return;
    nlohmann::json line = nlohmann::json::object();
    line["ts"] = now_utc();
    line["level"] = name(level);
    line["event"] = event;
    line["msg"] = msg;
    if (fields.is_object())
        for (const auto& [k, v] : fields.items()) line[k] = v;
    // One write per line, so lines from the two sides of a pipe never interleave.
    const std::string text =
        line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    std::fwrite(text.data(), 1, text.size(), stderr);
    std::fflush(stderr);
}

}  // namespace gimbal_track
