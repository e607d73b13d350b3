// The MAVLink messages of a gimbal device link as JSON (degrees for quaternions and rates),
// for gimbal-sim's --rx-log and the export's track values.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

#include "mavlink/messages.hpp"

namespace gimbal::protocols {

// "heartbeat", "command_long", "gimbal_device_set_attitude", ... ("msg_<id>" otherwise).
std::string mavlink_message_name(const mavlink::Payload& payload);
// The message's fields; quaternions also as roll/pitch/yaw degrees.
nlohmann::json mavlink_message_json(const mavlink::Payload& payload);

}  // namespace gimbal::protocols
