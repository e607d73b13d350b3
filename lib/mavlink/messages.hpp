// The MAVLink messages gimbald reads from the autopilot (common.xml), in MAVLink units: the
// structs hold the wire values unchanged (degE7, mm, cm/s, cdeg, us), so a decode and an encode
// give back the same bytes. Each struct names its id, its wire length without extension fields
// and its CRC_EXTRA (the checksum of its definition, which catches a sender with another one).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include "mavlink/camera_messages.hpp"
#include "mavlink/gimbal_messages.hpp"

namespace gimbal::mavlink {

// A char[N] field of common.xml: the text's first N bytes, zero-padded (no terminator when
// the text fills the field).
template <std::size_t N>
void set_text(std::array<std::uint8_t, N>& field, std::string_view text) {
    field.fill(0);
    for (std::size_t i = 0; i < text.size() && i < N; ++i)
        field[i] = static_cast<std::uint8_t>(text[i]);
}

// HEARTBEAT (0). Wire order: custom_mode, type, autopilot, base_mode, system_status,
// mavlink_version.
struct Heartbeat {
    static constexpr std::uint32_t id = 0;
    static constexpr std::uint8_t length = 9;
    static constexpr std::uint8_t max_length = length;
    static constexpr std::uint8_t crc_extra = 50;

    std::uint32_t custom_mode = 0;
    std::uint8_t type = 0, autopilot = 0, base_mode = 0, system_status = 0, mavlink_version = 3;
    bool operator==(const Heartbeat&) const = default;
};

// SYSTEM_TIME (2). Wire order: time_unix_usec, time_boot_ms.
struct SystemTime {
    static constexpr std::uint32_t id = 2;
    static constexpr std::uint8_t length = 12;
    static constexpr std::uint8_t max_length = length;
    static constexpr std::uint8_t crc_extra = 137;

    std::uint64_t time_unix_usec = 0;  // us since the UNIX epoch; 0: the sender has no time
    std::uint32_t time_boot_ms = 0;
    bool operator==(const SystemTime&) const = default;
};

// ATTITUDE (30). Radians and rad/s, aeronautical frame (Z down, X front, Y right).
struct Attitude {
    static constexpr std::uint32_t id = 30;
    static constexpr std::uint8_t length = 28;
    static constexpr std::uint8_t max_length = length;
    static constexpr std::uint8_t crc_extra = 39;

    std::uint32_t time_boot_ms = 0;
    float roll = 0, pitch = 0, yaw = 0, rollspeed = 0, pitchspeed = 0, yawspeed = 0;
    bool operator==(const Attitude&) const = default;
};

// GLOBAL_POSITION_INT (33). lat/lon degE7, alt (MSL) and relative_alt mm, vx/vy/vz cm/s
// (north, east, down), hdg cdeg (hdg_unknown when the sender has none).
struct GlobalPositionInt {
    static constexpr std::uint32_t id = 33;
    static constexpr std::uint8_t length = 28;
    static constexpr std::uint8_t max_length = length;
    static constexpr std::uint8_t crc_extra = 104;
    static constexpr std::uint16_t hdg_unknown = 0xFFFF;

    std::uint32_t time_boot_ms = 0;
    std::int32_t lat = 0, lon = 0, alt = 0, relative_alt = 0;
    std::int16_t vx = 0, vy = 0, vz = 0;
    std::uint16_t hdg = 0;
    bool operator==(const GlobalPositionInt&) const = default;
};

// RC_CHANNELS (65). chan_raw[i] is chan<i+1>_raw in us (channel_unused when not used).
// Wire order: time_boot_ms, chan1_raw..chan18_raw, chancount, rssi.
struct RcChannels {
    static constexpr std::uint32_t id = 65;
    static constexpr std::uint8_t length = 42;
    static constexpr std::uint8_t max_length = length;
    static constexpr std::uint8_t crc_extra = 118;
    static constexpr std::uint16_t channel_unused = 0xFFFF;
    static constexpr std::uint8_t rssi_unknown = 0xFF;

    std::uint32_t time_boot_ms = 0;
    std::uint8_t chancount = 0;
    std::array<std::uint16_t, 18> chan_raw{};
    std::uint8_t rssi = 0;
    bool operator==(const RcChannels&) const = default;
};

using Payload =
    std::variant<Heartbeat, SystemTime, Attitude, GlobalPositionInt, RcChannels, CommandInt,
                 CommandLong, CommandAck, CameraInformation, CameraSettings, StorageInformation,
                 CameraCaptureStatus, VideoStreamInformation, VideoStreamStatus, CameraFovStatus,
                 CameraTrackingImageStatus, CameraTrackingGeoStatus, GimbalManagerInformation,
                 GimbalManagerStatus, GimbalManagerSetAttitude, GimbalDeviceInformation,
                 GimbalDeviceSetAttitude, GimbalDeviceAttitudeStatus, AutopilotStateForGimbalDevice,
                 GimbalManagerSetPitchyaw>;

// The 13 bytes after a signed v2 frame. `verified`: the framer had the key and the 48-bit
// signature matched (replay is checked by SigningStreams, which needs the local clock).
struct Signature {
    std::uint8_t link_id = 0;
    std::uint64_t timestamp = 0;  // 10 us units since 2015-01-01 00:00 UTC
    bool verified = false;
    bool operator==(const Signature&) const = default;
};

// One decoded message with its frame header.
struct Message {
    std::uint8_t version = 2;  // 1: magic 0xFE, 2: magic 0xFD
    std::uint8_t seq = 0, sysid = 0, compid = 0;
    std::uint32_t msgid = 0;
    Payload payload;
    std::optional<Signature> signature;  // signed v2 frames only
    bool operator==(const Message&) const = default;
};

// What the framer needs to know about a message id.
struct MessageInfo {
    std::uint32_t id;
    std::uint8_t length;  // wire length without extension fields
    std::uint8_t crc_extra;
    std::uint8_t max_length;  // with extension fields
};

// nullptr for an id this codec does not decode.
const MessageInfo* find_message(std::uint32_t msgid);

std::uint32_t message_id(const Payload& payload);

// MAV_MODE_FLAG bits of Heartbeat::base_mode.
inline constexpr std::uint8_t mav_mode_flag_safety_armed = 128;
inline constexpr std::uint8_t mav_mode_flag_custom_mode_enabled = 1;

// MAV_STATE values of Heartbeat::system_status.
enum class MavState : std::uint8_t {
    uninit = 0,
    boot = 1,
    calibrating = 2,
    standby = 3,
    active = 4,
    critical = 5,
    emergency = 6,
    poweroff = 7,
    flight_termination = 8,
};

// MAV_AUTOPILOT_INVALID: the heartbeat of a GCS, gimbal, camera... rather than an autopilot.
inline constexpr std::uint8_t mav_autopilot_invalid = 8;
// MAV_TYPE_GCS.
inline constexpr std::uint8_t mav_type_gcs = 6;

inline bool armed(const Heartbeat& hb) {
    return (hb.base_mode & mav_mode_flag_safety_armed) != 0;
}

inline MavState system_state(const Heartbeat& hb) {
    return static_cast<MavState>(hb.system_status);
}

// True when the sender is a flight controller (what "the first autopilot heard" means).
inline bool is_autopilot(const Heartbeat& hb) {
    return hb.autopilot != mav_autopilot_invalid && hb.type != mav_type_gcs;
}

}  // namespace gimbal::mavlink
