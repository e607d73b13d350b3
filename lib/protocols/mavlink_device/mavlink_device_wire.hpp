// What gimbald sends on a MAVLink device link: v2 frames from its own system and component,
// with their sequence counter; and the vehicle's state as the device needs it. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mavlink/framing.hpp"
#include "mavlink/messages.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::protocols {

class MavlinkSender {
  public:
    MavlinkSender(std::uint8_t system_id, std::uint8_t component_id)
        : system_id_(system_id), component_id_(component_id) {}
    std::vector<std::uint8_t> frame(const mavlink::Payload& payload) {
        return mavlink::encode_v2(payload, system_id_, component_id_, seq_++);
    }

  private:
    std::uint8_t system_id_;
    std::uint8_t component_id_;
    std::uint8_t seq_ = 0;
};

// The aircraft as the steering and STATE telemetry need it: position (MSL), attitude and
// velocity from its autopilot (GLOBAL_POSITION_INT, ATTITUDE), in degrees, metres, m/s.
struct VehicleFix {
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;
    double vn_mps = 0, ve_mps = 0, vd_mps = 0;
    double yaw_rate_dps = 0;
};

// The fix when the vehicle state has a fresh position and attitude, else nullopt.
std::optional<VehicleFix> vehicle_fix(const vehicle::VehicleState& vehicle, double now_s);

// AUTOPILOT_STATE_FOR_GIMBAL_DEVICE for the device from the fix (nullopt: nothing valid,
// the message says so with NaNs and no estimator bits).
mavlink::AutopilotStateForGimbalDevice autopilot_state(const std::optional<VehicleFix>& fix,
                                                       std::uint64_t time_boot_us,
                                                       std::uint8_t target_system,
                                                       std::uint8_t target_component);

}  // namespace gimbal::protocols
