#include "command/envelope.hpp"

#include "command/catalogue.hpp"

namespace gimbal::command {

// Thin views of the catalogue, kept for their callers in daemon/.
bool is_common_command(std::string_view cmd) {
    const auto* c = find_command(cmd);
    return c && c->scope != Scope::protocol;
}

bool is_open_command(std::string_view cmd) {
    const auto* c = find_command(cmd);
    return c && !c->needs_token;
}

bool is_global_command(std::string_view cmd) {
    const auto* c = find_command(cmd);
    return c && c->scope == Scope::daemon;
}

nlohmann::json ok_reply(const std::optional<nlohmann::json>& id, std::string_view cmd,
                        const std::optional<std::string>& gimbal, nlohmann::json results) {
    nlohmann::json reply = nlohmann::json::object();
    if (id) reply["id"] = *id;
    reply["ok"] = true;
    reply["cmd"] = cmd;
    if (gimbal) reply["gimbal"] = *gimbal;
    if (results.is_object())
        for (auto& [k, v] : results.items()) reply[k] = std::move(v);
    return reply;
}

nlohmann::json error_reply(const std::optional<nlohmann::json>& id,
                           const std::optional<std::string>& cmd, const Error& error) {
    nlohmann::json reply = nlohmann::json::object();
    if (id) reply["id"] = *id;
    reply["ok"] = false;
    reply["cmd"] = cmd ? nlohmann::json(*cmd) : nlohmann::json(nullptr);
    reply["error"] = {{"code", error.code}, {"message", error.message}};
    return reply;
}

}  // namespace gimbal::command
