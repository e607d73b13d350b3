// Something a subscriber is told about as it happens (contract section 4.1, event kinds).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace gimbal::state {

struct Event {
    std::string kind;  // link, mode, stare_start, debug, laser_deadman, lost
    nlohmann::json fields = nlohmann::json::object();
};

}  // namespace gimbal::state
