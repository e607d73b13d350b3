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

std::optional<EnvelopeError> parse_envelope(std::string_view datagram,
                                            bool (*known_cmd)(std::string_view), JsonEnvelope& out) {
    if (auto refused = check_request_limits(datagram)) {
        // Not parsed, so nothing is echoed; a too_large reply says "id": null outright.
        const bool too_large = refused->code == code::too_large;
        return EnvelopeError{
            std::move(*refused),
            too_large ? std::optional<nlohmann::json>(nlohmann::json(nullptr)) : std::nullopt,
            std::nullopt};
    }
    nlohmann::json j = nlohmann::json::parse(datagram, nullptr, false);
    if (j.is_discarded() || !j.is_object())
        return EnvelopeError{
            {code::bad_json, "the datagram is not a JSON object"}, std::nullopt, std::nullopt};

    EnvelopeError failure{{}, std::nullopt, std::nullopt};
    auto fail = [&failure](ErrorCode c, std::string message) {
        failure.error = Error{c, std::move(message)};
        return failure;
    };
    if (auto it = j.find("id"); it != j.end()) failure.id = *it;

    auto cmd = j.find("cmd");
    if (cmd == j.end()) return fail(code::unknown_cmd, "missing 'cmd'");
    if (!cmd->is_string()) return fail(code::unknown_cmd, "'cmd' must be a string");
    failure.cmd = cmd->get<std::string>();
    if (!known_cmd(*failure.cmd))
        return fail(code::unknown_cmd, "unknown command '" + *failure.cmd + "'");

    if (auto g = j.find("gimbal"); g != j.end() && !g->is_null()) {
        if (!g->is_string()) return fail(code::bad_request, "'gimbal' must be a string");
        out.gimbal = g->get<std::string>();
    }
    if (auto t = j.find("token"); t != j.end() && !t->is_null()) {
        if (!t->is_string()) return fail(code::bad_request, "'token' must be a string");
        out.token = t->get<std::string>();
    }
    out.cmd = *failure.cmd;
    out.id = failure.id;
    out.request = std::move(j);
    return std::nullopt;
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
