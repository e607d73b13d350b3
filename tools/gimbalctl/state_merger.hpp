// `watch` of a delta stream (contract section 14): each gimbal's STATE merged from the
// pushes, so every line printed holds the whole STATE as of that push.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "json_types.hpp"

namespace gimbalctl {

class StateMerger {
  public:
    // A state message with "full" (a delta stream's push) comes back with "state" holding the
    // merged STATE of that stream (`stream`: the gimbal, or station and gimbal); nullopt
    // while no full STATE of that stream has arrived (a patch has nothing to apply to yet).
    // Any other message comes back as it is.
    std::optional<Json> merge(const std::string& stream, Json message);

  private:
    std::map<std::string, nlohmann::json> states_;
};

}  // namespace gimbalctl
