// Roles a key holds and the role each command needs (contract section 10).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

namespace gimbal::auth {

enum class Role : std::uint8_t { observe = 1, control = 2, laser = 4 };

// A set of roles as bits.
class Roles {
  public:
    Roles() = default;
    void add(Role r) { bits_ = static_cast<std::uint8_t>(bits_ | static_cast<std::uint8_t>(r)); }
    bool has(Role r) const { return (bits_ & static_cast<std::uint8_t>(r)) != 0; }
    bool operator==(const Roles&) const = default;

  private:
    std::uint8_t bits_ = 0;
};

std::optional<Role> parse_role(std::string_view name);
std::string_view to_string(Role role);

// The role `cmd` needs; nullopt for the open commands (ping, version, list). A `laser`
// command needs `laser` only when it fires; with fire false it is a control command.
std::optional<Role> required_role(std::string_view cmd, const nlohmann::json& request);

}  // namespace gimbal::auth
