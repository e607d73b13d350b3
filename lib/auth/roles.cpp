#include "auth/roles.hpp"

namespace gimbal::auth {

std::optional<Role> parse_role(std::string_view name) {
    if (name == "observe") return Role::observe;
    if (name == "control") return Role::control;
    if (name == "laser") return Role::laser;
    return std::nullopt;
}

std::string_view to_string(Role role) {
    switch (role) {
        case Role::observe:
            return "observe";
        case Role::control:
            return "control";
        case Role::laser:
            return "laser";
    }
    return "?";
}

std::optional<Role> required_role(std::string_view cmd, const nlohmann::json& request) {
    if (cmd == "ping" || cmd == "version" || cmd == "list") return std::nullopt;
    if (cmd == "state" || cmd == "subscribe" || cmd == "unsubscribe") return Role::observe;
    if (cmd == "laser") {
        // Anything but an explicit `fire: false` counts as firing here; the command parser
        // then rejects a non-boolean `fire` on its own.
        const auto fire = request.find("fire");
        const bool holds_fire =
            fire == request.end() || !(fire->is_boolean() && !fire->get<bool>());
        return holds_fire ? Role::laser : Role::control;
    }
    return Role::control;
}

}  // namespace gimbal::auth
