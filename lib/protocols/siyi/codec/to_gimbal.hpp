// Messages a controller sends to a SIYI gimbal camera ("Send Data Format" of each command in
// SDK v0.1.1 chapter 2). Angles: SIYI's yaw is positive to the LEFT (counter-clockwise seen
// from above; ArduPilot's AP_Mount_Siyi negates it to get a right-positive yaw), pitch
// positive up; both in 0.1 degree on the wire (docs/siyi.md "Angles").
#pragma once

#include <cstdint>
#include <string_view>

#include "protocols/siyi/codec/commands.hpp"
#include "protocols/siyi/codec/fields.hpp"

namespace gimbal::siyi {

// 0x00 TCP heartbeat (TCP links only; the SDK's frame carries one zero byte, no reply).
struct TcpHeartbeat {
    static constexpr std::uint8_t cmd = cmd::tcp_heartbeat;
    static constexpr std::string_view name = "tcp_heartbeat";
    template <class V>
    void fields(V& v) {
        v.reserved(u8);
    }
};

// The requests that carry no data: the gimbal answers with the reply of the same CMD_ID.
template <std::uint8_t Cmd>
struct EmptyRequest {
    static constexpr std::uint8_t cmd = Cmd;
    template <class V>
    void fields(V&) {}
};

struct FirmwareVersionRequest : EmptyRequest<cmd::firmware_version> {
    static constexpr std::string_view name = "firmware_version_request";
};
struct HardwareIdRequest : EmptyRequest<cmd::hardware_id> {
    static constexpr std::string_view name = "hardware_id_request";
};
struct CameraSystemInfoRequest : EmptyRequest<cmd::camera_system_info> {
    static constexpr std::string_view name = "camera_system_info_request";
};
struct GimbalAttitudeRequest : EmptyRequest<cmd::gimbal_attitude> {
    static constexpr std::string_view name = "gimbal_attitude_request";
};
struct LaserDistanceRequest : EmptyRequest<cmd::laser_distance> {
    static constexpr std::string_view name = "laser_distance_request";
};
struct ZoomRangeRequest : EmptyRequest<cmd::zoom_range> {
    static constexpr std::string_view name = "zoom_range_request";
};
struct LaserTargetRequest : EmptyRequest<cmd::laser_target> {
    static constexpr std::string_view name = "laser_target_request";
};
struct CurrentZoomRequest : EmptyRequest<cmd::current_zoom> {
    static constexpr std::string_view name = "current_zoom_request";
};
struct GimbalModeRequest : EmptyRequest<cmd::gimbal_mode> {
    static constexpr std::string_view name = "gimbal_mode_request";
};

// 0x04 auto focus at a point of the video (touch_x/touch_y in stream pixels). Older SDK
// editions sent only the first byte; the touch point is optional on decode.
struct AutoFocus {
    static constexpr std::uint8_t cmd = cmd::auto_focus;
    static constexpr std::string_view name = "auto_focus";
    bool trigger = true;  // "1: Trigger single autofocus"
    std::uint16_t touch_x = 0, touch_y = 0;
    template <class V>
    void fields(V& v) {
        v.field("trigger", trigger, u8);
        v.optional();
        v.field("touch_x", touch_x, u16);
        v.field("touch_y", touch_y, u16);
    }
};

// 0x05 manual zoom (with auto focus).
struct ManualZoom {
    static constexpr std::uint8_t cmd = cmd::manual_zoom;
    static constexpr std::string_view name = "manual_zoom";
    ZoomStep zoom = ZoomStep::stop;
    template <class V>
    void fields(V& v) {
        v.field("zoom", zoom, i8);
    }
};

// 0x06 manual focus.
struct ManualFocus {
    static constexpr std::uint8_t cmd = cmd::manual_focus;
    static constexpr std::string_view name = "manual_focus";
    FocusStep focus = FocusStep::stop;
    template <class V>
    void fields(V& v) {
        v.field("focus", focus, i8);
    }
};

// 0x07 gimbal rotation: speeds -100..100 (percent of the gimbal's top rate; ArduPilot takes
// 100 for 90 deg/s). Positive turn_yaw turns right, positive turn_pitch up; 0 0 stops.
struct GimbalRotation {
    static constexpr std::uint8_t cmd = cmd::gimbal_rotation;
    static constexpr std::string_view name = "gimbal_rotation";
    std::int8_t turn_yaw = 0, turn_pitch = 0;
    template <class V>
    void fields(V& v) {
        v.field("turn_yaw", turn_yaw, i8);
        v.field("turn_pitch", turn_pitch, i8);
    }
};

// 0x08 one-key centering.
struct Center {
    static constexpr std::uint8_t cmd = cmd::center;
    static constexpr std::string_view name = "center";
    CenterPosition position = CenterPosition::one_key_center;
    template <class V>
    void fields(V& v) {
        v.field("position", position, u8);
    }
};

// 0x0C photo, recording and motion mode (no reply; the camera answers 0x0B for photos and
// recordings).
struct Capture {
    static constexpr std::uint8_t cmd = cmd::capture;
    static constexpr std::string_view name = "capture";
    CaptureFunction function = CaptureFunction::take_photo;
    template <class V>
    void fields(V& v) {
        v.field("function", function, u8);
    }
};

// 0x0E absolute angles (SIYI frame: yaw positive left, pitch positive up).
struct SetGimbalAttitude {
    static constexpr std::uint8_t cmd = cmd::set_gimbal_attitude;
    static constexpr std::string_view name = "set_gimbal_attitude";
    double yaw = 0, pitch = 0;  // degrees
    template <class V>
    void fields(V& v) {
        v.field("yaw", yaw, i16, 10.0);
        v.field("pitch", pitch, i16, 10.0);
    }
};

// 0x0F absolute zoom, one decimal ("0x1 ~ 0x1E" . "0x0 ~ 0x9").
struct AbsoluteZoom {
    static constexpr std::uint8_t cmd = cmd::absolute_zoom;
    static constexpr std::string_view name = "absolute_zoom";
    double zoom = 1.0;
    template <class V>
    void fields(V& v) {
        v.zoom("zoom", zoom);
    }
};

// 0x22 the aircraft's attitude (NED, yaw -> pitch -> roll; 20-50 Hz recommended; no reply).
struct AircraftAttitude {
    static constexpr std::uint8_t cmd = cmd::aircraft_attitude;
    static constexpr std::string_view name = "aircraft_attitude";
    std::uint32_t time_boot_ms = 0;
    float roll = 0, pitch = 0, yaw = 0;                 // radians
    float roll_rate = 0, pitch_rate = 0, yaw_rate = 0;  // radians/s
    template <class V>
    void fields(V& v) {
        v.field("time_boot_ms", time_boot_ms, u32);
        v.field("roll", roll, f32, 1.0, Unit::radians);
        v.field("pitch", pitch, f32, 1.0, Unit::radians);
        v.field("yaw", yaw, f32, 1.0, Unit::radians);
        v.field("roll_rate", roll_rate, f32, 1.0, Unit::radians);
        v.field("pitch_rate", pitch_rate, f32, 1.0, Unit::radians);
        v.field("yaw_rate", yaw_rate, f32, 1.0, Unit::radians);
    }
};

// 0x25 ask the gimbal to push a data stream at a rate.
struct DataStreamRequest {
    static constexpr std::uint8_t cmd = cmd::data_stream;
    static constexpr std::string_view name = "data_stream_request";
    StreamType type = StreamType::attitude;
    StreamRate rate = StreamRate::off;
    template <class V>
    void fields(V& v) {
        v.field("type", type, u8);
        v.field("rate", rate, u8);
    }
};

// 0x30 UTC time, microseconds since the UNIX epoch.
struct SetUtcTime {
    static constexpr std::uint8_t cmd = cmd::utc_time;
    static constexpr std::string_view name = "set_utc_time";
    std::uint64_t unix_time_us = 0;
    template <class V>
    void fields(V& v) {
        v.field("unix_time_us", unix_time_us, u64);
    }
};

// 0x3E the aircraft's raw GPS position and velocity (no reply).
struct RawGps {
    static constexpr std::uint8_t cmd = cmd::raw_gps;
    static constexpr std::string_view name = "raw_gps";
    std::uint32_t time_boot_ms = 0;
    double lat = 0, lon = 0;                // degrees (degE7 on the wire)
    double alt_msl = 0, alt_ellipsoid = 0;  // metres (cm on the wire)
    double vn = 0, ve = 0, vd = 0;          // m/s (mm/s on the wire)
    template <class V>
    void fields(V& v) {
        v.field("time_boot_ms", time_boot_ms, u32);
        v.field("lat", lat, i32, 1e7);
        v.field("lon", lon, i32, 1e7);
        v.field("alt_msl", alt_msl, i32, 100.0);
        v.field("alt_ellipsoid", alt_ellipsoid, i32, 100.0);
        v.field("vn", vn, i32, 1000.0);
        v.field("ve", ve, i32, 1000.0);
        v.field("vd", vd, i32, 1000.0);
    }
};

}  // namespace gimbal::siyi
