// The commands a SIYI camera takes - `position`, `center`, `rate`, `camera_zoom`,
// `geopoint` and `path` - read with the catalogue's parameters (lib/command/catalogue.cpp) and
// turned into what to send now and what gimbald holds the camera to (SiyiSteering). Pure: a refused
// command changes nothing.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "command/result.hpp"
#include "protocols/siyi/siyi_steering.hpp"

namespace gimbal::protocols {

struct SiyiCommandContext {
    double now_s = 0;                       // monotonic, for a rate's impulse, a path's timing
    std::optional<double> vehicle_yaw_deg;  // with the vehicle's fix: its heading
    bool has_vehicle_fix = false;           // geopoint and path aim from its position
    double geoid_undulation_m = 0;          // alt_ref "msl"
    const siyi::ModelInfo* model = nullptr;
};

struct SiyiPlan {
    std::vector<siyi::ToGimbal> send;  // at once
    // Replaces the held target (nullptr: keeps it). Shared rather than optional: GCC 12 at
    // -O2 warns falsely (-Wmaybe-uninitialized) when an optional<SiyiHold> is moved.
    std::shared_ptr<const SiyiHold> hold;
};

bool is_siyi_command(std::string_view cmd);

command::Result<SiyiPlan> plan_siyi_command(std::string_view cmd, const nlohmann::json& request,
                                            const SiyiCommandContext& context);

}  // namespace gimbal::protocols
