// `mavlink` (contract sections 8 and 14): the MAVLink gimbal manager on the vehicle link -
// ids, extra UDP targets, signing and whether it obeys commands. Declared once here and read
// and written by the generic reader (lib/config/fields.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/fields.hpp"

namespace gimbal::daemon {

// MAVLink gimbal manager (contract section 8): the vehicle endpoint becomes two-way.
struct MavlinkConfig {
    bool gimbal_manager = false;
    std::optional<std::uint8_t> system_id;  // empty: vehicle.system_id, else the autopilot's
    std::uint8_t component_id = 154;        // MAV_COMP_ID_GIMBAL
    std::vector<std::string> targets;       // "host:port", UDP
    std::optional<std::string> signing_key_file;
    // false: the endpoint only reports; every command is DENIED (contract section 14).
    bool commands = true;
    // Home altitude MSL (m) for relative-altitude ROIs when no autopilot reports one.
    std::optional<double> home_alt_msl;
    // Where the signing streams' last timestamps survive a restart; null: in
    // $STATE_DIRECTORY (systemd), else nowhere.
    std::optional<std::string> signing_state_file;
    bool operator==(const MavlinkConfig&) const = default;
};

bool valid_target(const std::string& text);  // "host:port", port 1..65535

template <class V>
void fields(V& v, MavlinkConfig& c) {
    v.boolean("gimbal_manager", c.gimbal_manager);
    v.optional_integer("system_id", c.system_id, {1, 255});
    v.integer("component_id", c.component_id, {1, 255});
    v.string_list("targets", c.targets, valid_target, "must be an array of \"host:port\" strings",
                  "must be \"host:port\" with a port 1..65535");
    v.optional_string("signing_key_file", c.signing_key_file, "must be null or a file path");
    v.optional_string("signing_state_file", c.signing_state_file, "must be null or a file path");
    v.boolean("commands", c.commands);
    v.optional_number("home_alt_msl", c.home_alt_msl, {-1000, 10000});
}

}  // namespace gimbal::daemon
