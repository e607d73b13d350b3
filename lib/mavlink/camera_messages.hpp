// The MAVLink messages of the camera protocol (common.xml) that gimbald sends as a camera
// component (interface contract section 16), beside CAMERA_INFORMATION and CAMERA_FOV_STATUS
// in gimbal_messages.hpp. As there, the structs hold wire values unchanged; `length` is the
// wire length without extension fields, `max_length` with them; the comment gives the wire
// order (base fields by type size, largest first; extensions in declaration order). CRC_EXTRA
// values were computed from the common.xml definitions.
#pragma once

#include <array>
#include <cstdint>

#include "mavlink/gimbal_messages.hpp"

namespace gimbal::mavlink {

// CAMERA_SETTINGS (260). Wire order: time_boot_ms, mode_id; extensions zoomLevel, focusLevel,
// camera_device_id.
struct CameraSettings {
    static constexpr std::uint32_t id = 260;
    static constexpr std::uint8_t length = 5;
    static constexpr std::uint8_t max_length = 14;
    static constexpr std::uint8_t crc_extra = 146;

    std::uint32_t time_boot_ms = 0;
    std::uint8_t mode_id = 0;
    float zoom_level = nan_f, focus_level = nan_f;  // percent of the full range, NaN: unknown
    std::uint8_t camera_device_id = 0;
    bool operator==(const CameraSettings&) const = default;
};

// STORAGE_INFORMATION (261). Wire order: time_boot_ms, total_capacity, used_capacity,
// available_capacity, read_speed, write_speed, storage_id, storage_count, status; extensions
// type, name[32], storage_usage.
struct StorageInformation {
    static constexpr std::uint32_t id = 261;
    static constexpr std::uint8_t length = 27;
    static constexpr std::uint8_t max_length = 61;
    static constexpr std::uint8_t crc_extra = 179;

    std::uint32_t time_boot_ms = 0;
    float total_capacity = 0, used_capacity = 0, available_capacity = 0, read_speed = 0,
          write_speed = 0;
    std::uint8_t storage_id = 0, storage_count = 0, status = 0, type = 0;
    std::array<std::uint8_t, 32> name{};
    std::uint8_t storage_usage = 0;
    bool operator==(const StorageInformation&) const = default;
};

// CAMERA_CAPTURE_STATUS (262). Wire order: time_boot_ms, image_interval, recording_time_ms,
// available_capacity, image_status, video_status; extensions image_count, camera_device_id.
struct CameraCaptureStatus {
    static constexpr std::uint32_t id = 262;
    static constexpr std::uint8_t length = 18;
    static constexpr std::uint8_t max_length = 23;
    static constexpr std::uint8_t crc_extra = 12;

    std::uint32_t time_boot_ms = 0;
    float image_interval = 0;
    std::uint32_t recording_time_ms = 0;
    float available_capacity = 0;
    std::uint8_t image_status = 0, video_status = 0;
    std::int32_t image_count = 0;
    std::uint8_t camera_device_id = 0;
    bool operator==(const CameraCaptureStatus&) const = default;
};

// VIDEO_STREAM_INFORMATION (269). Wire order: framerate, bitrate, flags, resolution_h,
// resolution_v, rotation, hfov, stream_id, count, type, name[32], uri[160]; extensions
// encoding, camera_device_id.
struct VideoStreamInformation {
    static constexpr std::uint32_t id = 269;
    static constexpr std::uint8_t length = 213;
    static constexpr std::uint8_t max_length = 215;
    static constexpr std::uint8_t crc_extra = 109;

    float framerate = 0;
    std::uint32_t bitrate = 0;
    std::uint16_t flags = 0, resolution_h = 0, resolution_v = 0, rotation = 0, hfov = 0;
    std::uint8_t stream_id = 0, count = 0, type = 0;
    std::array<std::uint8_t, 32> name{};
    std::array<std::uint8_t, 160> uri{};
    std::uint8_t encoding = 0, camera_device_id = 0;
    bool operator==(const VideoStreamInformation&) const = default;
};

// VIDEO_STREAM_STATUS (270). Wire order: framerate, bitrate, flags, resolution_h,
// resolution_v, rotation, hfov, stream_id; extension camera_device_id.
struct VideoStreamStatus {
    static constexpr std::uint32_t id = 270;
    static constexpr std::uint8_t length = 19;
    static constexpr std::uint8_t max_length = 20;
    static constexpr std::uint8_t crc_extra = 59;

    float framerate = 0;
    std::uint32_t bitrate = 0;
    std::uint16_t flags = 0, resolution_h = 0, resolution_v = 0, rotation = 0, hfov = 0;
    std::uint8_t stream_id = 0, camera_device_id = 0;
    bool operator==(const VideoStreamStatus&) const = default;
};

// CAMERA_TRACKING_IMAGE_STATUS (275). Wire order: point_x, point_y, radius, rec_top_x,
// rec_top_y, rec_bottom_x, rec_bottom_y, tracking_status, tracking_mode, target_data;
// extension camera_device_id. Image coordinates 0..1 (left/top 0), NaN unknown.
struct CameraTrackingImageStatus {
    static constexpr std::uint32_t id = 275;
    static constexpr std::uint8_t length = 31;
    static constexpr std::uint8_t max_length = 32;
    static constexpr std::uint8_t crc_extra = 126;

    float point_x = nan_f, point_y = nan_f, radius = nan_f;
    float rec_top_x = nan_f, rec_top_y = nan_f, rec_bottom_x = nan_f, rec_bottom_y = nan_f;
    std::uint8_t tracking_status = 0, tracking_mode = 0, target_data = 0;
    std::uint8_t camera_device_id = 0;
    bool operator==(const CameraTrackingImageStatus&) const = default;
};

// CAMERA_TRACKING_GEO_STATUS (276). Wire order: lat, lon (degE7), alt (m, AMSL), h_acc, v_acc,
// vel_n, vel_e, vel_d, vel_acc, dist, hdg, hdg_acc, tracking_status; extension
// camera_device_id. NaN where unknown.
struct CameraTrackingGeoStatus {
    static constexpr std::uint32_t id = 276;
    static constexpr std::uint8_t length = 49;
    static constexpr std::uint8_t max_length = 50;
    static constexpr std::uint8_t crc_extra = 18;

    std::int32_t lat = 0, lon = 0;
    float alt = nan_f, h_acc = nan_f, v_acc = nan_f, vel_n = nan_f, vel_e = nan_f, vel_d = nan_f,
          vel_acc = nan_f, dist = nan_f, hdg = nan_f, hdg_acc = nan_f;
    std::uint8_t tracking_status = 0;
    std::uint8_t camera_device_id = 0;
    bool operator==(const CameraTrackingGeoStatus&) const = default;
};

// The camera protocol's commands (MAV_CMD).
namespace camera_cmd {
inline constexpr std::uint16_t set_message_interval = 511;
inline constexpr std::uint16_t request_camera_information = 521;
inline constexpr std::uint16_t request_camera_settings = 522;
inline constexpr std::uint16_t request_storage_information = 525;
inline constexpr std::uint16_t storage_format = 526;
inline constexpr std::uint16_t request_camera_capture_status = 527;
inline constexpr std::uint16_t reset_camera_settings = 529;
inline constexpr std::uint16_t set_camera_mode = 530;
inline constexpr std::uint16_t set_camera_focus = 532;
inline constexpr std::uint16_t set_camera_source = 534;
inline constexpr std::uint16_t image_start_capture = 2000;
inline constexpr std::uint16_t image_stop_capture = 2001;
inline constexpr std::uint16_t request_camera_image_capture = 2002;
inline constexpr std::uint16_t camera_track_point = 2004;
inline constexpr std::uint16_t camera_track_rectangle = 2005;
inline constexpr std::uint16_t camera_stop_tracking = 2010;
inline constexpr std::uint16_t video_start_capture = 2500;
inline constexpr std::uint16_t video_stop_capture = 2501;
inline constexpr std::uint16_t video_start_streaming = 2502;
inline constexpr std::uint16_t video_stop_streaming = 2503;
inline constexpr std::uint16_t request_video_stream_information = 2504;
inline constexpr std::uint16_t request_video_stream_status = 2505;
}  // namespace camera_cmd

// CAMERA_CAP_FLAGS (camera_cap_has_basic_zoom is in gimbal_messages.hpp).
namespace camera_cap {
inline constexpr std::uint32_t has_basic_zoom = 64;
inline constexpr std::uint32_t has_video_stream = 256;
inline constexpr std::uint32_t has_tracking_point = 512;
inline constexpr std::uint32_t has_tracking_rectangle = 1024;
inline constexpr std::uint32_t has_tracking_geo_status = 2048;
}  // namespace camera_cap

// VIDEO_STREAM_TYPE, VIDEO_STREAM_STATUS_FLAGS, VIDEO_STREAM_ENCODING.
namespace video_stream {
inline constexpr std::uint8_t type_rtsp = 0;
inline constexpr std::uint8_t type_mpeg_ts = 3;
inline constexpr std::uint16_t flag_running = 1;
inline constexpr std::uint16_t flag_thermal = 2;
inline constexpr std::uint8_t encoding_unknown = 0;
inline constexpr std::uint8_t encoding_h264 = 1;
inline constexpr std::uint8_t encoding_h265 = 2;
}  // namespace video_stream

// CAMERA_MODE, STORAGE_STATUS, CAMERA_TRACKING_STATUS_FLAGS, CAMERA_TRACKING_MODE,
// CAMERA_TRACKING_TARGET_DATA.
inline constexpr std::uint8_t camera_mode_video = 1;
inline constexpr std::uint8_t storage_status_not_supported = 3;
namespace tracking {
inline constexpr std::uint8_t status_idle = 0;
inline constexpr std::uint8_t status_active = 1;
inline constexpr std::uint8_t status_error = 2;
inline constexpr std::uint8_t mode_none = 0;
inline constexpr std::uint8_t mode_point = 1;
inline constexpr std::uint8_t mode_rectangle = 2;
inline constexpr std::uint8_t target_data_in_status = 4;
}  // namespace tracking

// MAV_TYPE_CAMERA; MAV_COMP_ID_CAMERA (the first of MAV_COMP_ID_CAMERA..CAMERA6).
inline constexpr std::uint8_t mav_type_camera = 30;
inline constexpr std::uint8_t mav_comp_id_camera = 100;

}  // namespace gimbal::mavlink
