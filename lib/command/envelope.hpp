// The outside of every reply on the command socket (contract section 4): the two reply
// shapes, and views of the catalogue for the daemon (a request is read by request.hpp).
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

// Commands every gimbal understands (section 4.1).
bool is_common_command(std::string_view cmd);
// Commands that need no token even when command.token is set.
bool is_open_command(std::string_view cmd);
// Commands that take no `gimbal`.
bool is_global_command(std::string_view cmd);

nlohmann::json ok_reply(const std::optional<nlohmann::json>& id, std::string_view cmd,
                        const std::optional<std::string>& gimbal, nlohmann::json results);
nlohmann::json error_reply(const std::optional<nlohmann::json>& id,
                           const std::optional<std::string>& cmd, const Error& error);

}  // namespace gimbal::command
