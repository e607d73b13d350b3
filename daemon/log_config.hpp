// `log` (contract section 6): level, format and an optional file. Declared once here and
// read and written by the generic reader (lib/config/fields.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "config/fields.hpp"
#include "logging.hpp"

namespace gimbal::daemon {

struct LogConfig {
    log::Level level = log::Level::info;
    log::Format format = log::Format::json;
    std::optional<std::string> file;
    log::Settings settings() const { return {level, format, file}; }
    bool operator==(const LogConfig&) const = default;
};

inline constexpr std::array<config::Named<log::Level>, 5> log_level_names{
    {{"trace", log::Level::trace},
     {"debug", log::Level::debug},
     {"info", log::Level::info},
     {"warn", log::Level::warn},
     {"error", log::Level::error}}};
inline constexpr std::array<config::Named<log::Format>, 2> log_format_names{
    {{"json", log::Format::json}, {"text", log::Format::text}}};

template <class V>
void fields(V& v, LogConfig& c) {
    v.choice("level", c.level, log_level_names);
    v.choice("format", c.format, log_format_names);
    v.optional_string("file", c.file, "must be null or a file path");
}

}  // namespace gimbal::daemon
