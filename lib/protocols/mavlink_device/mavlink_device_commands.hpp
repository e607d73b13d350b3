// The commands a MAVLink gimbal device takes (contract section 19): `position`, `rate`,
// `geopoint` and `path`, with the catalogue's parameters (lib/command/catalogue.cpp), turned
// into what gimbald holds the device to (MavlinkDeviceSteering). Pure: a refused command
// changes nothing.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "command/result.hpp"
#include "protocols/mavlink_device/mavlink_device_steering.hpp"

namespace gimbal::protocols {

struct DeviceCommandContext {
    double now_s = 0;                // monotonic, for a rate's impulse and a path's timing
    bool has_vehicle_fix = false;    // geopoint and path aim from the aircraft's position
    double vehicle_heading_deg = 0;  // with the fix: a stabilized position's yaw from north
    double geoid_undulation_m = 0;   // alt_ref "msl"
};

bool is_device_command(std::string_view cmd);

// The hold for `cmd`, or the error to reply with.
command::Result<Hold> plan_device_command(std::string_view cmd, const nlohmann::json& request,
                                          const DeviceCommandContext& context);

}  // namespace gimbal::protocols
