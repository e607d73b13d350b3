#include "protocols/mavlink_device/mavlink_device_json.hpp"

#include <cmath>

#include "protocols/mavlink_device/mavlink_device_state.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

constexpr double rad_to_deg = 180.0 / 3.14159265358979323846;

json number(float v, double scale = 1.0) {
    return std::isfinite(v) ? json(state::round_decimals(v * scale, 6)) : json(nullptr);
}

json quaternion(const std::array<float, 4>& q) {
    json j = {{"q", {number(q[0]), number(q[1]), number(q[2]), number(q[3])}}};
    const auto e = euler_of(q);
    j["roll"] = e ? json(state::angle_deg(e->roll_deg)) : json(nullptr);
    j["pitch"] = e ? json(state::angle_deg(e->pitch_deg)) : json(nullptr);
    j["yaw"] = e ? json(state::angle_deg(e->yaw_deg)) : json(nullptr);
    return j;
}

}  // namespace

std::string mavlink_message_name(const mavlink::Payload& payload) {
    using namespace mavlink;
    if (std::holds_alternative<Heartbeat>(payload)) return "heartbeat";
    if (std::holds_alternative<CommandLong>(payload)) return "command_long";
    if (std::holds_alternative<CommandAck>(payload)) return "command_ack";
    if (std::holds_alternative<GimbalDeviceInformation>(payload))
        return "gimbal_device_information";
    if (std::holds_alternative<GimbalDeviceSetAttitude>(payload))
        return "gimbal_device_set_attitude";
    if (std::holds_alternative<GimbalDeviceAttitudeStatus>(payload))
        return "gimbal_device_attitude_status";
    if (std::holds_alternative<AutopilotStateForGimbalDevice>(payload))
        return "autopilot_state_for_gimbal_device";
    return "msg_" + std::to_string(message_id(payload));
}

json mavlink_message_json(const mavlink::Payload& payload) {
    using namespace mavlink;
    if (const auto* m = std::get_if<Heartbeat>(&payload))
        return {
            {"type", m->type}, {"autopilot", m->autopilot}, {"system_status", m->system_status}};
    if (const auto* m = std::get_if<CommandLong>(&payload)) {
        json params = json::array();
        for (const float p : m->param) params.push_back(number(p));
        return {{"command", m->command},
                {"params", params},
                {"target_system", m->target_system},
                {"target_component", m->target_component}};
    }
    if (const auto* m = std::get_if<CommandAck>(&payload))
        return {{"command", m->command}, {"result", m->result}};
    if (const auto* m = std::get_if<GimbalDeviceSetAttitude>(&payload)) {
        json j = quaternion(m->q);
        j["angular_velocity"] = {number(m->angular_velocity_x, rad_to_deg),
                                 number(m->angular_velocity_y, rad_to_deg),
                                 number(m->angular_velocity_z, rad_to_deg)};
        j["flags"] = m->flags;
        j["target_system"] = m->target_system;
        j["target_component"] = m->target_component;
        return j;
    }
    if (const auto* m = std::get_if<GimbalDeviceAttitudeStatus>(&payload)) {
        json j = quaternion(m->q);
        j["time_boot_ms"] = m->time_boot_ms;
        j["angular_velocity"] = {number(m->angular_velocity_x, rad_to_deg),
                                 number(m->angular_velocity_y, rad_to_deg),
                                 number(m->angular_velocity_z, rad_to_deg)};
        j["flags"] = m->flags;
        j["failure_flags"] = m->failure_flags;
        return j;
    }
    if (const auto* m = std::get_if<AutopilotStateForGimbalDevice>(&payload)) {
        json j = quaternion(m->q);
        j["time_boot_us"] = m->time_boot_us;
        j["v_ned"] = {number(m->vx), number(m->vy), number(m->vz)};
        j["feed_forward_yaw_rate"] = number(m->feed_forward_angular_velocity_z, rad_to_deg);
        j["estimator_status"] = m->estimator_status;
        return j;
    }
    if (const auto* m = std::get_if<GimbalDeviceInformation>(&payload))
        return {{"firmware_version", m->firmware_version}, {"cap_flags", m->cap_flags}};
    return json::object();
}

}  // namespace gimbal::protocols
