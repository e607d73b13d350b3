#include "protocols/mavlink_device/mavlink_device_flags.hpp"

#include <array>
#include <string_view>
#include <utility>

namespace gimbal::protocols {

namespace {

using Bit = std::pair<std::uint32_t, std::string_view>;

// common.xml GIMBAL_DEVICE_CAP_FLAGS.
constexpr std::array cap_bits{
    Bit{1, "has_retract"},
    Bit{2, "has_neutral"},
    Bit{4, "has_roll_axis"},
    Bit{8, "has_roll_follow"},
    Bit{16, "has_roll_lock"},
    Bit{32, "has_pitch_axis"},
    Bit{64, "has_pitch_follow"},
    Bit{128, "has_pitch_lock"},
    Bit{256, "has_yaw_axis"},
    Bit{512, "has_yaw_follow"},
    Bit{1024, "has_yaw_lock"},
    Bit{2048, "supports_infinite_yaw"},
    Bit{4096, "supports_yaw_in_earth_frame"},
    Bit{8192, "has_rc_inputs"},
    Bit{65536, "can_point_location_local"},
    Bit{131072, "can_point_location_global"},
};

// common.xml GIMBAL_DEVICE_ERROR_FLAGS.
constexpr std::array failure_bits{
    Bit{1, "at_roll_limit"},   Bit{2, "at_pitch_limit"}, Bit{4, "at_yaw_limit"},
    Bit{8, "encoder_error"},   Bit{16, "power_error"},   Bit{32, "motor_error"},
    Bit{64, "software_error"}, Bit{128, "comms_error"},  Bit{256, "calibration_running"},
    Bit{512, "no_manager"},
};

template <std::size_t N>
std::vector<std::string> names_of(std::uint32_t flags, const std::array<Bit, N>& bits) {
    std::vector<std::string> out;
    for (const auto& [bit, name] : bits)
        if ((flags & bit) != 0) out.emplace_back(name);
    return out;
}

}  // namespace

std::vector<std::string> cap_flag_names(std::uint32_t cap_flags) {
    return names_of(cap_flags, cap_bits);
}

std::vector<std::string> failure_flag_names(std::uint32_t failure_flags) {
    return names_of(failure_flags, failure_bits);
}

bool yaw_in_earth_frame(std::uint16_t flags) {
    if ((flags & device_flags::yaw_in_earth_frame) != 0) return true;
    if ((flags & device_flags::yaw_in_vehicle_frame) != 0) return false;
    return (flags & device_flags::yaw_lock) != 0;
}

}  // namespace gimbal::protocols
