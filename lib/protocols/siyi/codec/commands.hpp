// SIYI SDK command ids (CMD_ID) and the enumerations their messages carry, as "SIYI Gimbal
// Camera External SDK Protocol" v0.1.1 (2025-02-26) chapter 2 defines them. Only the
// commands gimbald uses are declared; docs/siyi.md lists them with their sources.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "protocols/siyi/codec/fields.hpp"

namespace gimbal::siyi {

namespace cmd {
inline constexpr std::uint8_t tcp_heartbeat = 0x00;
inline constexpr std::uint8_t firmware_version = 0x01;
inline constexpr std::uint8_t hardware_id = 0x02;
inline constexpr std::uint8_t auto_focus = 0x04;
inline constexpr std::uint8_t manual_zoom = 0x05;
inline constexpr std::uint8_t manual_focus = 0x06;
inline constexpr std::uint8_t gimbal_rotation = 0x07;
inline constexpr std::uint8_t center = 0x08;
inline constexpr std::uint8_t camera_system_info = 0x0A;
inline constexpr std::uint8_t function_feedback = 0x0B;
inline constexpr std::uint8_t capture = 0x0C;
inline constexpr std::uint8_t gimbal_attitude = 0x0D;
inline constexpr std::uint8_t set_gimbal_attitude = 0x0E;
inline constexpr std::uint8_t absolute_zoom = 0x0F;
inline constexpr std::uint8_t laser_distance = 0x15;
inline constexpr std::uint8_t zoom_range = 0x16;
inline constexpr std::uint8_t laser_target = 0x17;
inline constexpr std::uint8_t current_zoom = 0x18;
inline constexpr std::uint8_t gimbal_mode = 0x19;
inline constexpr std::uint8_t aircraft_attitude = 0x22;
inline constexpr std::uint8_t data_stream = 0x25;
inline constexpr std::uint8_t magnetic_encoder = 0x26;
inline constexpr std::uint8_t utc_time = 0x30;
inline constexpr std::uint8_t raw_gps = 0x3E;
}  // namespace cmd

// 0x05 zoom: 1 zoom in, 0 stop ("send after release"), -1 zoom out.
enum class ZoomStep : std::int8_t { out = -1, stop = 0, in = 1 };
// 0x06 focus: 1 far, 0 stop, -1 near.
enum class FocusStep : std::int8_t { near = -1, stop = 0, far = 1 };

// 0x08 center_pos.
enum class CenterPosition : std::uint8_t {
    one_key_center = 1,
    center_down = 2,
    center = 3,
    down = 4
};

// 0x0C func_type.
enum class CaptureFunction : std::uint8_t {
    take_photo = 0,
    hdr_toggle = 1,
    record_toggle = 2,  // "start recording": toggles recording on and off
    lock_mode = 3,
    follow_mode = 4,
    fpv_mode = 5,
    hdmi_output = 6,       // takes effect after a reboot (A8 mini)
    cvbs_output = 7,       // same
    video_output_off = 8,  // same
    tilt_down = 9,
    zoom_linkage = 10,
};

// 0x0A record_sta.
enum class RecordStatus : std::uint8_t { off = 0, recording = 1, no_card = 2, data_loss = 3 };
// 0x0A gimbal_motion_mode and 0x19 gimbal_mode.
enum class MotionMode : std::uint8_t { lock = 0, follow = 1, fpv = 2 };
// 0x0A gimbal_mounting_dir.
enum class MountingDirection : std::uint8_t { reserved = 0, normal = 1, inverted = 2 };
// 0x0A video_hdmi_or_cvbs.
enum class VideoOutput : std::uint8_t { hdmi = 0, cvbs = 1 };

// 0x0B info_type.
enum class FeedbackInfo : std::uint8_t {
    photo_ok = 0,
    photo_failed = 1,  // "check TF card"
    hdr_on = 2,
    hdr_off = 3,
    record_failed = 4,  // "check TF card"
    record_started = 5,
    record_stopped = 6,
};

// 0x25 data_type.
enum class StreamType : std::uint8_t {
    attitude = 1,
    laser_range = 2,  // pushed at the rangefinder's own rate whatever the requested one
    magnetic_encoder = 3,
    motor_voltage = 4,
};
// 0x25 data_freq.
enum class StreamRate : std::uint8_t {
    off = 0,
    hz2 = 1,
    hz4 = 2,
    hz5 = 3,
    hz10 = 4,
    hz20 = 5,
    hz50 = 6,
    hz100 = 7,
};

// The rate a StreamRate code stands for, in Hz (0 for off or an unknown code).
double stream_rate_hz(StreamRate rate);

#define GIMBAL_SIYI_ENUM_NAMES(E, ...)                        \
    inline constexpr EnumName<E> E##_names[] = {__VA_ARGS__}; \
    constexpr std::span<const EnumName<E>> enum_names(E) {    \
        return E##_names;                                     \
    }

GIMBAL_SIYI_ENUM_NAMES(ZoomStep, {ZoomStep::out, "out"}, {ZoomStep::stop, "stop"},
                       {ZoomStep::in, "in"})
GIMBAL_SIYI_ENUM_NAMES(FocusStep, {FocusStep::near, "near"}, {FocusStep::stop, "stop"},
                       {FocusStep::far, "far"})
GIMBAL_SIYI_ENUM_NAMES(CenterPosition, {CenterPosition::one_key_center, "one_key_center"},
                       {CenterPosition::center_down, "center_down"},
                       {CenterPosition::center, "center"}, {CenterPosition::down, "down"})
GIMBAL_SIYI_ENUM_NAMES(
    CaptureFunction, {CaptureFunction::take_photo, "take_photo"},
    {CaptureFunction::hdr_toggle, "hdr_toggle"}, {CaptureFunction::record_toggle, "record_toggle"},
    {CaptureFunction::lock_mode, "lock_mode"}, {CaptureFunction::follow_mode, "follow_mode"},
    {CaptureFunction::fpv_mode, "fpv_mode"}, {CaptureFunction::hdmi_output, "hdmi_output"},
    {CaptureFunction::cvbs_output, "cvbs_output"},
    {CaptureFunction::video_output_off, "video_output_off"},
    {CaptureFunction::tilt_down, "tilt_down"}, {CaptureFunction::zoom_linkage, "zoom_linkage"})
GIMBAL_SIYI_ENUM_NAMES(RecordStatus, {RecordStatus::off, "off"},
                       {RecordStatus::recording, "recording"}, {RecordStatus::no_card, "no_card"},
                       {RecordStatus::data_loss, "data_loss"})
GIMBAL_SIYI_ENUM_NAMES(MotionMode, {MotionMode::lock, "lock"}, {MotionMode::follow, "follow"},
                       {MotionMode::fpv, "fpv"})
GIMBAL_SIYI_ENUM_NAMES(MountingDirection, {MountingDirection::reserved, "reserved"},
                       {MountingDirection::normal, "normal"},
                       {MountingDirection::inverted, "inverted"})
GIMBAL_SIYI_ENUM_NAMES(VideoOutput, {VideoOutput::hdmi, "hdmi"}, {VideoOutput::cvbs, "cvbs"})
GIMBAL_SIYI_ENUM_NAMES(FeedbackInfo, {FeedbackInfo::photo_ok, "photo_ok"},
                       {FeedbackInfo::photo_failed, "photo_failed"},
                       {FeedbackInfo::hdr_on, "hdr_on"}, {FeedbackInfo::hdr_off, "hdr_off"},
                       {FeedbackInfo::record_failed, "record_failed"},
                       {FeedbackInfo::record_started, "record_started"},
                       {FeedbackInfo::record_stopped, "record_stopped"})
GIMBAL_SIYI_ENUM_NAMES(StreamType, {StreamType::attitude, "attitude"},
                       {StreamType::laser_range, "laser_range"},
                       {StreamType::magnetic_encoder, "magnetic_encoder"},
                       {StreamType::motor_voltage, "motor_voltage"})
GIMBAL_SIYI_ENUM_NAMES(StreamRate, {StreamRate::off, "off"}, {StreamRate::hz2, "2hz"},
                       {StreamRate::hz4, "4hz"}, {StreamRate::hz5, "5hz"},
                       {StreamRate::hz10, "10hz"}, {StreamRate::hz20, "20hz"},
                       {StreamRate::hz50, "50hz"}, {StreamRate::hz100, "100hz"})

#undef GIMBAL_SIYI_ENUM_NAMES

}  // namespace gimbal::siyi
