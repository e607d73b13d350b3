// The MAVLink messages of the command and gimbal/camera protocols (common.xml) that gimbald
// reads and writes as a gimbal manager (interface contract section 8). As in messages.hpp the
// structs hold wire values unchanged (radians, degE7, mm); `length` is the wire length without
// extension fields, `max_length` with them. Field order in each comment is the wire order
// (MAVLink 2 sorts the base fields by type size, largest first; extensions follow in
// declaration order). CRC_EXTRA values were computed from the common.xml definitions.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

namespace gimbal::mavlink {

inline constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();

// COMMAND_INT (75). Wire order: param1..4, x, y, z, command, target_system, target_component,
// frame, current, autocontinue.
struct CommandInt {
    static constexpr std::uint32_t id = 75;
    static constexpr std::uint8_t length = 35;
    static constexpr std::uint8_t max_length = 35;
    static constexpr std::uint8_t crc_extra = 158;

    float param1 = 0, param2 = 0, param3 = 0, param4 = 0;
    std::int32_t x = 0, y = 0;
    float z = 0;
    std::uint16_t command = 0;
    std::uint8_t target_system = 0, target_component = 0, frame = 0, current = 0, autocontinue = 0;
    bool operator==(const CommandInt&) const = default;
};

// COMMAND_LONG (76). Wire order: param1..7, command, target_system, target_component,
// confirmation.
struct CommandLong {
    static constexpr std::uint32_t id = 76;
    static constexpr std::uint8_t length = 33;
    static constexpr std::uint8_t max_length = 33;
    static constexpr std::uint8_t crc_extra = 152;

    std::array<float, 7> param{};
    std::uint16_t command = 0;
    std::uint8_t target_system = 0, target_component = 0, confirmation = 0;
    bool operator==(const CommandLong&) const = default;
};

// COMMAND_ACK (77). Wire order: command, result; extensions progress, result_param2,
// target_system, target_component.
struct CommandAck {
    static constexpr std::uint32_t id = 77;
    static constexpr std::uint8_t length = 3;
    static constexpr std::uint8_t max_length = 10;
    static constexpr std::uint8_t crc_extra = 143;

    std::uint16_t command = 0;
    std::uint8_t result = 0;
    std::uint8_t progress = 0;
    std::int32_t result_param2 = 0;
    std::uint8_t target_system = 0, target_component = 0;
    bool operator==(const CommandAck&) const = default;
};

// CAMERA_INFORMATION (259). Wire order: time_boot_ms, firmware_version, focal_length,
// sensor_size_h, sensor_size_v, flags, resolution_h, resolution_v, cam_definition_version,
// vendor_name[32], model_name[32], lens_id, cam_definition_uri[140]; extensions
// gimbal_device_id, camera_device_id.
struct CameraInformation {
    static constexpr std::uint32_t id = 259;
    static constexpr std::uint8_t length = 235;
    static constexpr std::uint8_t max_length = 237;
    static constexpr std::uint8_t crc_extra = 92;

    std::uint32_t time_boot_ms = 0, firmware_version = 0;
    float focal_length = 0, sensor_size_h = 0, sensor_size_v = 0;
    std::uint32_t flags = 0;
    std::uint16_t resolution_h = 0, resolution_v = 0, cam_definition_version = 0;
    std::array<std::uint8_t, 32> vendor_name{}, model_name{};
    std::uint8_t lens_id = 0;
    std::array<std::uint8_t, 140> cam_definition_uri{};
    std::uint8_t gimbal_device_id = 0, camera_device_id = 0;
    bool operator==(const CameraInformation&) const = default;
};

// CAMERA_FOV_STATUS (271). Wire order: time_boot_ms, lat_camera, lon_camera, alt_camera,
// lat_image, lon_image, alt_image, q[4], hfov, vfov; extension camera_device_id.
// Unknown positions are INT32_MAX, unknown angles NaN.
struct CameraFovStatus {
    static constexpr std::uint32_t id = 271;
    static constexpr std::uint8_t length = 52;
    static constexpr std::uint8_t max_length = 53;
    static constexpr std::uint8_t crc_extra = 22;
    static constexpr std::int32_t unknown = std::numeric_limits<std::int32_t>::max();

    std::uint32_t time_boot_ms = 0;
    std::int32_t lat_camera = unknown, lon_camera = unknown, alt_camera = unknown;
    std::int32_t lat_image = unknown, lon_image = unknown, alt_image = unknown;
    std::array<float, 4> q{nan_f, nan_f, nan_f, nan_f};
    float hfov = nan_f, vfov = nan_f;
    std::uint8_t camera_device_id = 0;
    bool operator==(const CameraFovStatus&) const = default;
};

// GIMBAL_MANAGER_INFORMATION (280). Wire order: time_boot_ms, cap_flags, roll_min, roll_max,
// pitch_min, pitch_max, yaw_min, yaw_max, gimbal_device_id.
struct GimbalManagerInformation {
    static constexpr std::uint32_t id = 280;
    static constexpr std::uint8_t length = 33;
    static constexpr std::uint8_t max_length = 33;
    static constexpr std::uint8_t crc_extra = 70;

    std::uint32_t time_boot_ms = 0, cap_flags = 0;
    float roll_min = 0, roll_max = 0, pitch_min = 0, pitch_max = 0, yaw_min = 0, yaw_max = 0;
    std::uint8_t gimbal_device_id = 0;
    bool operator==(const GimbalManagerInformation&) const = default;
};

// GIMBAL_MANAGER_STATUS (281). Wire order: time_boot_ms, flags, gimbal_device_id,
// primary_control_sysid, primary_control_compid, secondary_control_sysid,
// secondary_control_compid.
struct GimbalManagerStatus {
    static constexpr std::uint32_t id = 281;
    static constexpr std::uint8_t length = 13;
    static constexpr std::uint8_t max_length = 13;
    static constexpr std::uint8_t crc_extra = 48;

    std::uint32_t time_boot_ms = 0, flags = 0;
    std::uint8_t gimbal_device_id = 0, primary_control_sysid = 0, primary_control_compid = 0,
                 secondary_control_sysid = 0, secondary_control_compid = 0;
    bool operator==(const GimbalManagerStatus&) const = default;
};

// GIMBAL_MANAGER_SET_ATTITUDE (282). Wire order: flags, q[4], angular_velocity_x/y/z,
// target_system, target_component, gimbal_device_id.
struct GimbalManagerSetAttitude {
    static constexpr std::uint32_t id = 282;
    static constexpr std::uint8_t length = 35;
    static constexpr std::uint8_t max_length = 35;
    static constexpr std::uint8_t crc_extra = 123;

    std::uint32_t flags = 0;
    std::array<float, 4> q{};
    float angular_velocity_x = nan_f, angular_velocity_y = nan_f, angular_velocity_z = nan_f;
    std::uint8_t target_system = 0, target_component = 0, gimbal_device_id = 0;
    bool operator==(const GimbalManagerSetAttitude&) const = default;
};

// GIMBAL_DEVICE_INFORMATION (283). Wire order: uid, time_boot_ms, firmware_version,
// hardware_version, roll_min, roll_max, pitch_min, pitch_max, yaw_min, yaw_max, cap_flags,
// custom_cap_flags, vendor_name[32], model_name[32], custom_name[32]; extensions
// gimbal_device_id, cap_flags2.
struct GimbalDeviceInformation {
    static constexpr std::uint32_t id = 283;
    static constexpr std::uint8_t length = 144;
    static constexpr std::uint8_t max_length = 149;
    static constexpr std::uint8_t crc_extra = 74;

    std::uint64_t uid = 0;
    std::uint32_t time_boot_ms = 0, firmware_version = 0, hardware_version = 0;
    float roll_min = nan_f, roll_max = nan_f, pitch_min = nan_f, pitch_max = nan_f, yaw_min = nan_f,
          yaw_max = nan_f;
    std::uint16_t cap_flags = 0, custom_cap_flags = 0;
    std::array<std::uint8_t, 32> vendor_name{}, model_name{}, custom_name{};
    std::uint8_t gimbal_device_id = 0;
    std::uint32_t cap_flags2 = 0;
    bool operator==(const GimbalDeviceInformation&) const = default;
};

// GIMBAL_DEVICE_SET_ATTITUDE (284). Wire order: q[4], angular_velocity_x/y/z, flags,
// target_system, target_component.
struct GimbalDeviceSetAttitude {
    static constexpr std::uint32_t id = 284;
    static constexpr std::uint8_t length = 32;
    static constexpr std::uint8_t max_length = 32;
    static constexpr std::uint8_t crc_extra = 99;

    std::array<float, 4> q{};
    float angular_velocity_x = nan_f, angular_velocity_y = nan_f, angular_velocity_z = nan_f;
    std::uint16_t flags = 0;
    std::uint8_t target_system = 0, target_component = 0;
    bool operator==(const GimbalDeviceSetAttitude&) const = default;
};

// GIMBAL_DEVICE_ATTITUDE_STATUS (285). Wire order: time_boot_ms, q[4], angular_velocity_x/y/z,
// failure_flags, flags, target_system, target_component; extensions delta_yaw,
// delta_yaw_velocity, gimbal_device_id.
struct GimbalDeviceAttitudeStatus {
    static constexpr std::uint32_t id = 285;
    static constexpr std::uint8_t length = 40;
    static constexpr std::uint8_t max_length = 49;
    static constexpr std::uint8_t crc_extra = 137;

    std::uint32_t time_boot_ms = 0;
    std::array<float, 4> q{};
    float angular_velocity_x = nan_f, angular_velocity_y = nan_f, angular_velocity_z = nan_f;
    std::uint32_t failure_flags = 0;
    std::uint16_t flags = 0;
    std::uint8_t target_system = 0, target_component = 0;
    float delta_yaw = nan_f, delta_yaw_velocity = nan_f;
    std::uint8_t gimbal_device_id = 0;
    bool operator==(const GimbalDeviceAttitudeStatus&) const = default;
};

// AUTOPILOT_STATE_FOR_GIMBAL_DEVICE (286): what a gimbal manager tells its gimbal device of the
// vehicle. Wire order: time_boot_us, q[4], q_estimated_delay_us, vx, vy, vz,
// v_estimated_delay_us, feed_forward_angular_velocity_z, estimator_status, target_system,
// target_component, landed_state; extension angular_velocity_z.
struct AutopilotStateForGimbalDevice {
    static constexpr std::uint32_t id = 286;
    static constexpr std::uint8_t length = 53;
    static constexpr std::uint8_t max_length = 57;
    static constexpr std::uint8_t crc_extra = 210;

    std::uint64_t time_boot_us = 0;
    std::array<float, 4> q{nan_f, nan_f, nan_f, nan_f};
    std::uint32_t q_estimated_delay_us = 0;
    float vx = nan_f, vy = nan_f, vz = nan_f;
    std::uint32_t v_estimated_delay_us = 0;
    float feed_forward_angular_velocity_z = nan_f;
    std::uint16_t estimator_status = 0;
    std::uint8_t target_system = 0, target_component = 0, landed_state = 0;
    float angular_velocity_z = 0;
    bool operator==(const AutopilotStateForGimbalDevice&) const = default;
};

// GIMBAL_MANAGER_SET_PITCHYAW (287). Wire order: flags, pitch, yaw, pitch_rate, yaw_rate,
// target_system, target_component, gimbal_device_id.
struct GimbalManagerSetPitchyaw {
    static constexpr std::uint32_t id = 287;
    static constexpr std::uint8_t length = 23;
    static constexpr std::uint8_t max_length = 23;
    static constexpr std::uint8_t crc_extra = 1;

    std::uint32_t flags = 0;
    float pitch = nan_f, yaw = nan_f, pitch_rate = nan_f, yaw_rate = nan_f;
    std::uint8_t target_system = 0, target_component = 0, gimbal_device_id = 0;
    bool operator==(const GimbalManagerSetPitchyaw&) const = default;
};

// Enumerations of common.xml used by the gimbal manager.
namespace mav_cmd {
inline constexpr std::uint16_t do_set_roi_location = 195;
inline constexpr std::uint16_t do_set_roi_none = 197;
inline constexpr std::uint16_t request_message = 512;
inline constexpr std::uint16_t set_camera_zoom = 531;
inline constexpr std::uint16_t do_gimbal_manager_pitchyaw = 1000;
inline constexpr std::uint16_t do_gimbal_manager_configure = 1001;
}  // namespace mav_cmd

enum class MavResult : std::uint8_t {
    accepted = 0,
    temporarily_rejected = 1,
    denied = 2,
    unsupported = 3,
    failed = 4,
};

namespace mav_frame {
inline constexpr std::uint8_t global = 0;
inline constexpr std::uint8_t global_relative_alt = 3;
inline constexpr std::uint8_t global_int = 5;
inline constexpr std::uint8_t global_relative_alt_int = 6;
inline constexpr std::uint8_t global_terrain_alt = 10;
inline constexpr std::uint8_t global_terrain_alt_int = 11;
}  // namespace mav_frame

// GIMBAL_MANAGER_FLAGS (and the GIMBAL_DEVICE_FLAGS they are based on: same bits).
namespace gimbal_flags {
inline constexpr std::uint32_t retract = 1;
inline constexpr std::uint32_t neutral = 2;
inline constexpr std::uint32_t roll_lock = 4;
inline constexpr std::uint32_t pitch_lock = 8;
inline constexpr std::uint32_t yaw_lock = 16;
inline constexpr std::uint32_t yaw_in_vehicle_frame = 32;
inline constexpr std::uint32_t yaw_in_earth_frame = 64;
inline constexpr std::uint32_t accepts_yaw_in_earth_frame = 128;
}  // namespace gimbal_flags

// GIMBAL_MANAGER_CAP_FLAGS (same bits as GIMBAL_DEVICE_CAP_FLAGS).
namespace gimbal_cap {
inline constexpr std::uint32_t has_neutral = 2;
inline constexpr std::uint32_t has_pitch_axis = 32;
inline constexpr std::uint32_t has_pitch_lock = 128;
inline constexpr std::uint32_t has_yaw_axis = 256;
inline constexpr std::uint32_t has_yaw_follow = 512;
inline constexpr std::uint32_t has_yaw_lock = 1024;
inline constexpr std::uint32_t supports_infinite_yaw = 2048;
inline constexpr std::uint32_t supports_yaw_in_earth_frame = 4096;
inline constexpr std::uint32_t can_point_location_global = 131072;
}  // namespace gimbal_cap

// GIMBAL_DEVICE_ERROR_FLAGS.
namespace gimbal_error {
inline constexpr std::uint32_t software_error = 64;
inline constexpr std::uint32_t comms_error = 128;
}  // namespace gimbal_error

// CAMERA_CAP_FLAGS_HAS_BASIC_ZOOM; CAMERA_ZOOM_TYPE.
inline constexpr std::uint32_t camera_cap_has_basic_zoom = 64;
namespace zoom_type {
inline constexpr int step = 0;
inline constexpr int continuous = 1;
inline constexpr int range = 2;
}  // namespace zoom_type

// MAV_TYPE_GIMBAL, MAV_COMP_ID_GIMBAL.
inline constexpr std::uint8_t mav_type_gimbal = 26;
inline constexpr std::uint8_t mav_comp_id_gimbal = 154;

}  // namespace gimbal::mavlink
