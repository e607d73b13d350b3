// The bit names of common.xml's gimbal device enumerations, for STATE `device` (contract
// section 19): GIMBAL_DEVICE_CAP_FLAGS and GIMBAL_DEVICE_ERROR_FLAGS without their prefixes,
// lower case ("has_pitch_axis", "motor_error").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gimbal::protocols {

// GIMBAL_DEVICE_FLAGS bits (and the MAVLink ids) this protocol uses.
namespace device_flags {
inline constexpr std::uint16_t roll_lock = 4;
inline constexpr std::uint16_t pitch_lock = 8;
inline constexpr std::uint16_t yaw_lock = 16;
inline constexpr std::uint16_t yaw_in_vehicle_frame = 32;
inline constexpr std::uint16_t yaw_in_earth_frame = 64;
}  // namespace device_flags

std::vector<std::string> cap_flag_names(std::uint32_t cap_flags);
std::vector<std::string> failure_flag_names(std::uint32_t failure_flags);

// Whether an attitude with these GIMBAL_DEVICE_FLAGS has its yaw from north (earth frame):
// YAW_IN_EARTH_FRAME, else not when YAW_IN_VEHICLE_FRAME, else (older devices) YAW_LOCK.
bool yaw_in_earth_frame(std::uint16_t flags);

}  // namespace gimbal::protocols
