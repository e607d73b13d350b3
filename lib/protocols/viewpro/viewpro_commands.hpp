// Viewpro commands of the contract (section 4.3): viewpro_output, viewpro_adjust and
// vehicle -> the 5-byte commands and IN1/IN2 frames to write. Pure.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "command/result.hpp"

namespace gimbal::command {

struct ViewproContext {
    double unix_time_s = 0;  // "now" for a vehicle command without `time` (UTC)
};

bool is_viewpro_command(std::string_view cmd);

std::optional<Error> plan_viewpro(std::string_view cmd, const nlohmann::json& request,
                                  const ViewproContext& context, Plan& plan);

}  // namespace gimbal::command
