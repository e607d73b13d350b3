#include "auth/roles.hpp"

#include "command/catalogue.hpp"

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
    const auto* spec = command::find_command(cmd);
    // An unknown command never runs (unknown_cmd); asking for control keeps it that way.
    if (!spec) return Role::control;
    switch (spec->access) {
        case command::Access::open:
            return std::nullopt;
        case command::Access::observe:
            return Role::observe;
        case command::Access::control:
            return Role::control;
        case command::Access::laser_when_firing: {
            // Anything but an explicit `fire: false` counts as firing here; the command
            // parser then rejects a non-boolean `fire` on its own.
            const auto fire = request.find("fire");
            const bool holds_fire =
                fire == request.end() || !(fire->is_boolean() && !fire->get<bool>());
            return holds_fire ? Role::laser : Role::control;
        }
    }
    return Role::control;
}

}  // namespace gimbal::auth
