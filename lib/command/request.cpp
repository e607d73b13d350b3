#include "command/request.hpp"

#include <atomic>

#include "command/request_limits.hpp"

namespace gimbal::command {

namespace {

std::atomic<std::uint64_t> parses{0};

const nlohmann::json* find_value(const nlohmann::json& object, std::string_view key) {
    if (!object.is_object()) return nullptr;
    const auto it = object.find(std::string(key));
    if (it == object.end() || it->is_null()) return nullptr;
    return &*it;
}

}  // namespace

bool is_envelope_key(std::string_view key) {
    return key == "cmd" || key == "id" || key == "gimbal" || key == "token" || key == "ts" ||
           key == "nonce";
}

std::optional<nlohmann::json> parse_object(std::string_view bytes) {
    parses.fetch_add(1, std::memory_order_relaxed);
    nlohmann::json j = nlohmann::json::parse(bytes, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return std::nullopt;
    return j;
}

std::uint64_t request_parses() {
    return parses.load(std::memory_order_relaxed);
}

Echo echo_of(const nlohmann::json& doc) {
    Echo e;
    if (!doc.is_object()) return e;
    if (const auto it = doc.find("id"); it != doc.end()) e.id = *it;
    if (const auto it = doc.find("cmd"); it != doc.end() && it->is_string())
        e.cmd = it->get<std::string>();
    return e;
}

Result<Envelope> read_envelope(const nlohmann::json& doc) {
    if (!doc.is_object()) return Error{code::bad_json, "the datagram is not a JSON object"};
    Envelope env;
    if (const auto it = doc.find("id"); it != doc.end()) env.id = *it;
    const auto cmd = doc.find("cmd");
    if (cmd == doc.end()) return Error{code::unknown_cmd, "missing 'cmd'"};
    if (!cmd->is_string()) return Error{code::unknown_cmd, "'cmd' must be a string"};
    env.spec = find_command(cmd->get_ref<const std::string&>());
    if (!env.spec)
        return Error{code::unknown_cmd,
                     "unknown command '" + cmd->get_ref<const std::string&>() + "'"};
    if (const auto* g = find_value(doc, "gimbal")) {
        if (!g->is_string()) return Error{code::bad_request, "'gimbal' must be a string"};
        env.gimbal = g->get<std::string>();
    }
    if (const auto* t = find_value(doc, "token")) {
        if (!t->is_string()) return Error{code::bad_request, "'token' must be a string"};
        env.token = t->get<std::string>();
    }
    return env;
}

Result<Request> parse_request(std::string_view bytes) {
    if (auto refused = check_request_limits(bytes)) return std::move(*refused);
    auto doc = parse_object(bytes);
    if (!doc) return Error{code::bad_json, "the datagram is not a JSON object"};
    auto env = read_envelope(*doc);
    if (!env) return env.error();
    Request r;
    static_cast<Envelope&>(r) = std::move(env).value();
    r.doc = std::move(*doc);
    return r;
}

}  // namespace gimbal::command
