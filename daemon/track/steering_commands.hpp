// The commands with which a client steers a gimbal itself (contract section 20): one of
// them, executed, ends a running visual track with reason `overridden`.
#pragma once

#include <algorithm>
#include <array>
#include <string_view>

namespace gimbald::track {

inline constexpr std::array<std::string_view, 8> steering_commands{
    "geopoint", "path", "position", "rate", "center", "point", "mode", "viewpro_adjust"};

inline bool is_steering_command(std::string_view cmd) {
    return std::find(steering_commands.begin(), steering_commands.end(), cmd) !=
           steering_commands.end();
}

}  // namespace gimbald::track
