// Messages a SIYI gimbal camera sends: the replies ("ACK Data Format" of each command in SDK
// v0.1.1 chapter 2; CTRL ack_pack, the camera's own SEQ) and the pushes of a data stream
// (0x25) or a capture (0x0B), which use the same layouts. Angles as in to_gimbal.hpp.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "protocols/siyi/codec/commands.hpp"
#include "protocols/siyi/codec/fields.hpp"

namespace gimbal::siyi {

// 0x01 firmware versions. The A8 mini sends only camera and gimbal (8 bytes); every version
// reads 0.0.0 for up to 30 s after power-on, until the camera has started.
struct FirmwareVersion {
    static constexpr std::uint8_t cmd = cmd::firmware_version;
    static constexpr std::string_view name = "firmware_version";
    std::uint32_t camera = 0, gimbal = 0, zoom = 0;  // version words (fields.hpp)
    template <class V>
    void fields(V& v) {
        v.version("camera", camera);
        v.version("gimbal", gimbal);
        v.optional();
        v.version("zoom", zoom);
    }
};

// 0x02 hardware id: a 10-digit ASCII string in 12 bytes; its first two characters name the
// product (protocols/siyi/codec/models.hpp).
struct HardwareId {
    static constexpr std::uint8_t cmd = cmd::hardware_id;
    static constexpr std::string_view name = "hardware_id";
    std::string id;
    template <class V>
    void fields(V& v) {
        v.text("id", id, 12);
    }
};

// The replies that say only "1: success, 0: error".
template <std::uint8_t Cmd>
struct StatusReply {
    static constexpr std::uint8_t cmd = Cmd;
    bool ok = true;
    template <class V>
    void fields(V& v) {
        v.field("ok", ok, u8);
    }
};

struct AutoFocusReply : StatusReply<cmd::auto_focus> {
    static constexpr std::string_view name = "auto_focus_reply";
};
struct ManualFocusReply : StatusReply<cmd::manual_focus> {
    static constexpr std::string_view name = "manual_focus_reply";
};
struct GimbalRotationReply : StatusReply<cmd::gimbal_rotation> {
    static constexpr std::string_view name = "gimbal_rotation_reply";
};
struct CenterReply : StatusReply<cmd::center> {
    static constexpr std::string_view name = "center_reply";
};
struct AbsoluteZoomReply : StatusReply<cmd::absolute_zoom> {
    static constexpr std::string_view name = "absolute_zoom_reply";
};

// 0x05 reply: the zoom reached, in tenths ("zoom_multiple / 10").
struct ManualZoomReply {
    static constexpr std::uint8_t cmd = cmd::manual_zoom;
    static constexpr std::string_view name = "manual_zoom_reply";
    double zoom = 1.0;
    template <class V>
    void fields(V& v) {
        v.field("zoom", zoom, u16, 10.0);
    }
};

// 0x0A camera system information. Firmware before the mounting direction sent 5 bytes
// (ArduPilot checked for 5, later 7); SDK v0.1.1 has 8.
struct CameraSystemInfo {
    static constexpr std::uint8_t cmd = cmd::camera_system_info;
    static constexpr std::string_view name = "camera_system_info";
    bool hdr = false;
    RecordStatus record = RecordStatus::off;
    MotionMode motion_mode = MotionMode::follow;
    MountingDirection mounting = MountingDirection::normal;
    VideoOutput video_output = VideoOutput::hdmi;
    bool zoom_linkage = false;
    template <class V>
    void fields(V& v) {
        v.reserved(u8);
        v.field("hdr", hdr, u8);
        v.reserved(u8);
        v.field("record", record, u8);
        v.field("motion_mode", motion_mode, u8);
        v.optional();
        v.field("mounting", mounting, u8);
        v.field("video_output", video_output, u8);
        v.field("zoom_linkage", zoom_linkage, u8);
    }
};

// 0x0B function feedback, pushed after a photo or a recording toggle.
struct FunctionFeedback {
    static constexpr std::uint8_t cmd = cmd::function_feedback;
    static constexpr std::string_view name = "function_feedback";
    FeedbackInfo info = FeedbackInfo::photo_ok;
    template <class V>
    void fields(V& v) {
        v.field("info", info, u8);
    }
};

// 0x0D attitude and gyro rates (reply to a request, or pushed by the 0x25 attitude stream).
// Yaw from the magnetic encoder, i.e. relative to the aircraft; pitch and roll stabilized.
struct GimbalAttitude {
    static constexpr std::uint8_t cmd = cmd::gimbal_attitude;
    static constexpr std::string_view name = "gimbal_attitude";
    double yaw = 0, pitch = 0, roll = 0;                 // degrees
    double yaw_rate = 0, pitch_rate = 0, roll_rate = 0;  // degrees/s
    template <class V>
    void fields(V& v) {
        v.field("yaw", yaw, i16, 10.0);
        v.field("pitch", pitch, i16, 10.0);
        v.field("roll", roll, i16, 10.0);
        v.field("yaw_rate", yaw_rate, i16, 10.0);
        v.field("pitch_rate", pitch_rate, i16, 10.0);
        v.field("roll_rate", roll_rate, i16, 10.0);
    }
};

// 0x0E reply: the angles when the command arrived.
struct SetGimbalAttitudeReply {
    static constexpr std::uint8_t cmd = cmd::set_gimbal_attitude;
    static constexpr std::string_view name = "set_gimbal_attitude_reply";
    double yaw = 0, pitch = 0, roll = 0;  // degrees
    template <class V>
    void fields(V& v) {
        v.field("yaw", yaw, i16, 10.0);
        v.field("pitch", pitch, i16, 10.0);
        v.field("roll", roll, i16, 10.0);
    }
};

// 0x15 laser range (ZT30), decimetres on the wire; 5-1200 m, 0 when out of range.
struct LaserDistance {
    static constexpr std::uint8_t cmd = cmd::laser_distance;
    static constexpr std::string_view name = "laser_distance";
    double distance = 0;  // metres
    template <class V>
    void fields(V& v) {
        v.field("distance", distance, u16, 10.0);
    }
};

// 0x16 the largest zoom the camera accepts now.
struct ZoomRange {
    static constexpr std::uint8_t cmd = cmd::zoom_range;
    static constexpr std::string_view name = "zoom_range";
    double zoom_max = 1.0;
    template <class V>
    void fields(V& v) {
        v.zoom("zoom_max", zoom_max);
    }
};

// 0x17 where the laser hits (ZT30). Note the order: longitude first.
struct LaserTarget {
    static constexpr std::uint8_t cmd = cmd::laser_target;
    static constexpr std::string_view name = "laser_target";
    double lon = 0, lat = 0;  // degrees (degE7 on the wire)
    template <class V>
    void fields(V& v) {
        v.field("lon", lon, i32, 1e7);
        v.field("lat", lat, i32, 1e7);
    }
};

// 0x18 the zoom now.
struct CurrentZoom {
    static constexpr std::uint8_t cmd = cmd::current_zoom;
    static constexpr std::string_view name = "current_zoom";
    double zoom = 1.0;
    template <class V>
    void fields(V& v) {
        v.zoom("zoom", zoom);
    }
};

// 0x19 motion mode.
struct GimbalMode {
    static constexpr std::uint8_t cmd = cmd::gimbal_mode;
    static constexpr std::string_view name = "gimbal_mode";
    MotionMode mode = MotionMode::follow;
    template <class V>
    void fields(V& v) {
        v.field("mode", mode, u8);
    }
};

// 0x25 reply: which stream the request set.
struct DataStreamReply {
    static constexpr std::uint8_t cmd = cmd::data_stream;
    static constexpr std::string_view name = "data_stream_reply";
    StreamType type = StreamType::attitude;
    template <class V>
    void fields(V& v) {
        v.field("type", type, u8);
    }
};

// 0x26 magnetic encoder angles (pushed by the 0x25 encoder stream).
struct MagneticEncoder {
    static constexpr std::uint8_t cmd = cmd::magnetic_encoder;
    static constexpr std::string_view name = "magnetic_encoder";
    double yaw = 0, pitch = 0, roll = 0;  // degrees
    template <class V>
    void fields(V& v) {
        v.field("yaw", yaw, i16, 10.0);
        v.field("pitch", pitch, i16, 10.0);
        v.field("roll", roll, i16, 10.0);
    }
};

// 0x30 reply: "1: Success, 0: Invalid time format" (int8_t).
struct SetUtcTimeReply {
    static constexpr std::uint8_t cmd = cmd::utc_time;
    static constexpr std::string_view name = "set_utc_time_reply";
    bool ok = true;
    template <class V>
    void fields(V& v) {
        v.field("ok", ok, i8);
    }
};

}  // namespace gimbal::siyi
