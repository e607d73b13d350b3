// The outside of every request and reply on the command socket (contract section 4):
// datagram -> validated envelope, and the two reply shapes.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "command/request_limits.hpp"
#include "command/result.hpp"

namespace gimbal::command {

inline constexpr std::size_t max_datagram = max_request_bytes;

struct JsonEnvelope {
    nlohmann::json request;  // the whole object
    std::string cmd;
    std::optional<nlohmann::json> id;  // echoed unchanged when given
    std::optional<std::string> gimbal;
    std::optional<std::string> token;
};

// What went wrong before a command could be looked at, with what the reply can still echo.
struct EnvelopeError {
    Error error;
    std::optional<nlohmann::json> id;
    std::optional<std::string> cmd;
};

// Commands every gimbal understands (section 4.1).
bool is_common_command(std::string_view cmd);
// Commands that need no token even when command.token is set.
bool is_open_command(std::string_view cmd);
// Commands that take no `gimbal`.
bool is_global_command(std::string_view cmd);

// Parses one datagram. `known_cmd` decides whether a command name exists at all.
// On success returns nullopt and fills `out`. A datagram over the limits of
// request_limits.hpp is refused before it is parsed: nothing of it is echoed (a too_large
// reply's id is null).
std::optional<EnvelopeError> parse_envelope(std::string_view datagram,
                                            bool (*known_cmd)(std::string_view), JsonEnvelope& out);

nlohmann::json ok_reply(const std::optional<nlohmann::json>& id, std::string_view cmd,
                        const std::optional<std::string>& gimbal, nlohmann::json results);
nlohmann::json error_reply(const std::optional<nlohmann::json>& id,
                           const std::optional<std::string>& cmd, const Error& error);

}  // namespace gimbal::command
