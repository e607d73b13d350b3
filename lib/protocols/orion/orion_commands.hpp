// Orion commands of the contract (section 4.2): a JSON request -> validated parameters ->
// the wire packets to write. Pure: nothing is sent here, and a refused command plans nothing.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "command/result.hpp"

namespace gimbal::command {

// What a command may depend on besides its parameters.
struct OrionContext {
    bool allow_fire = false;                          // laser.allow_fire
    bool allow_safety_bypass = false;                 // laser.allow_safety_bypass
    std::optional<double> geoid_undulation_m;         // from the latest telemetry
    std::optional<std::uint32_t> last_stare_time_ms;  // from the latest StareStart
};

bool is_orion_command(std::string_view cmd);

// Plans `cmd` from the request object (envelope keys cmd/id/gimbal/token are ignored).
// Returns the error to reply with, or nullopt with `plan` filled.
std::optional<Error> plan_orion(std::string_view cmd, const nlohmann::json& request,
                                const OrionContext& context, Plan& plan);

}  // namespace gimbal::command
