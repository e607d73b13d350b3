// ICD section "Packets used for gimbal configuration". The user sends these to configure the
// gimbal (a zero-length packet requests the current setting); the gimbal replies with the
// packet filled in.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

enum class UartProtocol : std::uint8_t {  // OrionProtocols_t
    no_change = 0,
    none = 1,
    use_default = 2,
    orion = 3,
    clevis = 4,
    clevis_raw = 5,
    nmea_gps = 6,
    ublox_gps = 7,
    novatel_gps = 8,
    mavlink_gps = 9,
    um7_mag = 10,
    sightline_video = 11,
    sensonor_imu = 12,
    dmu11_imu = 13,
    discovery = 14,
    airrobot = 15,
    proprietary1 = 16,
    proprietary2 = 17,
    flir = 18,
    epson_imu = 19,
    piksi = 20,
    wepilot = 21,
};
constexpr std::array<EnumName<UartProtocol>, 22> uart_protocol_names{{
    {UartProtocol::no_change, "no_change"},
    {UartProtocol::none, "none"},
    {UartProtocol::use_default, "default"},
    {UartProtocol::orion, "orion"},
    {UartProtocol::clevis, "clevis"},
    {UartProtocol::clevis_raw, "clevis_raw"},
    {UartProtocol::nmea_gps, "nmea_gps"},
    {UartProtocol::ublox_gps, "ublox_gps"},
    {UartProtocol::novatel_gps, "novatel_gps"},
    {UartProtocol::mavlink_gps, "mavlink_gps"},
    {UartProtocol::um7_mag, "um7_mag"},
    {UartProtocol::sightline_video, "sightline_video"},
    {UartProtocol::sensonor_imu, "sensonor_imu"},
    {UartProtocol::dmu11_imu, "dmu11_imu"},
    {UartProtocol::discovery, "discovery"},
    {UartProtocol::airrobot, "airrobot"},
    {UartProtocol::proprietary1, "proprietary1"},
    {UartProtocol::proprietary2, "proprietary2"},
    {UartProtocol::flir, "flir"},
    {UartProtocol::epson_imu, "epson_imu"},
    {UartProtocol::piksi, "piksi"},
    {UartProtocol::wepilot, "wepilot"},
}};
constexpr std::span<const EnumName<UartProtocol>> enum_names(UartProtocol) {
    return uart_protocol_names;
}

// OrionUartConfig (2): baud rate and protocol of a crown board UART. (The 0- and 1-byte
// request forms are below min_length: they are only sent, never decoded.)
struct UartConfig {
    static constexpr std::uint8_t id = pkt::uart_config;
    static constexpr std::string_view name = "uart_config";
    static constexpr std::size_t min_length = 5;
    static constexpr std::size_t max_length = 6;

    UserDataPort port = UserDataPort::ethernet;
    std::uint32_t baud = 0;  // bits per second, 0 = default for the port and protocol
    UartProtocol protocol = UartProtocol::no_change;
    bool temporary = false;  // true: the setting is lost at power cycle

    template <class V>
    void fields(V& v) {
        v.field("port", port, u8);
        v.field("baud", baud, u24);
        v.field("protocol", protocol, u8);
        v.optional();
        v.field("temporary", temporary, u8);
    }
};

// OrionLimitsData (34): pan/tilt limits of operation, [pan, tilt].
struct Limits {
    static constexpr std::uint8_t id = pkt::limits;
    static constexpr std::string_view name = "limits";
    static constexpr std::size_t min_length = 32;
    static constexpr std::size_t max_length = 34;

    std::array<double, num_gimbal_axes> min_pos{};          // rad
    std::array<double, num_gimbal_axes> max_pos{};          // rad
    std::array<double, num_gimbal_axes> max_vel{};          // rad/s
    std::array<double, num_gimbal_axes> max_accel{};        // rad/s^2
    std::array<double, num_gimbal_axes> cont_cur{};         // A
    std::array<double, num_gimbal_axes> peak_cur{};         // A
    std::array<double, num_gimbal_axes> peak_cur_time_s{};  // s
    std::array<double, num_gimbal_axes> init_cur{};         // A
    std::array<double, num_gimbal_axes> max_power{};        // W, 0 = no limit

    template <class V>
    void fields(V& v) {
        v.field("min_pos", min_pos, i16, 1000.0, Unit::radians);
        v.field("max_pos", max_pos, i16, 1000.0, Unit::radians);
        v.field("max_vel", max_vel, u16, 1000.0, Unit::radians);
        v.field("max_accel", max_accel, u16, 1.0, Unit::radians);
        v.field("cont_cur", cont_cur, u16, 1000.0);
        v.field("peak_cur", peak_cur, u16, 1000.0);
        v.field("peak_cur_time_s", peak_cur_time_s, u16, 1000.0);
        v.field("init_cur", init_cur, u16, 1000.0);
        v.optional();
        v.field("max_power", max_power, u8, 1.0);
    }
};

// InsOptions (216): configuration of the gimbal's inertial navigation system.
struct InsOptions {
    static constexpr std::uint8_t id = pkt::ins_options;
    static constexpr std::string_view name = "ins_options";
    static constexpr std::size_t min_length = 12;
    static constexpr std::size_t max_length = 28;

    bool enable_platform_rotation = false;
    bool enable_course_is_heading = false;
    bool disable_magnetometer = false;
    bool disable_gps = false;
    bool reset_ins = false;
    bool disable_gps_clock_error = false;
    bool enable_accel_bias = false;
    bool enable_tightly_coupled = false;
    bool use_phase_for_velocity = false;
    bool disable_l1 = false;
    bool disable_l2 = false;
    bool disable_l5 = false;
    // The ICD scales this B4 by 15/(5 deg) (0..5 deg in 1/3 deg steps); bits() has no Scale,
    // so it stays the raw step count.
    std::uint8_t elevation_mask_code = 0;
    bool enable_payload_ins = false;
    bool enable_non_linear_heading = false;
    bool enable_sensonor_mv = false;
    bool enable_hd25_payload_ins = false;
    std::uint8_t optical_flow_setting = 0;
    std::array<double, num_axes> gimbal_to_platform_euler{};  // rad, [roll, pitch, yaw]
    double initial_heading = 0;                               // rad
    std::array<double, 3> gps_lever_arm{};                    // m, [x, y, z]
    double heading_observation_bias_angle = 0;                // rad
    std::array<double, 3> second_gps_lever_arm{};             // m, [x, y, z]
    double align_heading_noise = 0;                           // rad, 0 = Align default

    template <class V>
    void fields(V& v) {
        v.bits("enable_platform_rotation", enable_platform_rotation, 1);
        v.bits("enable_course_is_heading", enable_course_is_heading, 1);
        v.bits("disable_magnetometer", disable_magnetometer, 1);
        v.bits("disable_gps", disable_gps, 1);
        v.bits("reset_ins", reset_ins, 1);
        v.bits("disable_gps_clock_error", disable_gps_clock_error, 1);
        v.bits("enable_accel_bias", enable_accel_bias, 1);
        v.bits("enable_tightly_coupled", enable_tightly_coupled, 1);
        v.bits("use_phase_for_velocity", use_phase_for_velocity, 1);
        v.bits("disable_l1", disable_l1, 1);
        v.bits("disable_l2", disable_l2, 1);
        v.bits("disable_l5", disable_l5, 1);
        v.bits("elevation_mask_code", elevation_mask_code, 4);
        v.bits("enable_payload_ins", enable_payload_ins, 1);
        v.bits("enable_non_linear_heading", enable_non_linear_heading, 1);
        v.bits("enable_sensonor_mv", enable_sensonor_mv, 1);
        v.bits("enable_hd25_payload_ins", enable_hd25_payload_ins, 1);
        v.bits("optical_flow_setting", optical_flow_setting, 4);
        v.reserved_bits(8);
        v.field("gimbal_to_platform_euler", gimbal_to_platform_euler, i16, 32767.0 / pi,
                Unit::radians);
        v.field("initial_heading", initial_heading, i16, 32767.0 / pi, Unit::radians);
        v.optional();
        v.field("gps_lever_arm", gps_lever_arm, i16, 1000.0);
        v.field("heading_observation_bias_angle", heading_observation_bias_angle, i16, 32767.0 / pi,
                Unit::radians);
        v.field("second_gps_lever_arm", second_gps_lever_arm, i16, 1000.0);
        v.field("align_heading_noise", align_heading_noise, u16, 65535.0 / pi, Unit::radians);
    }
};

// OrionNetworkSettings / OrionNetworkByteSettings (228): the ICD gives the addresses both as
// U32 and as U8[4]; both are the same big-endian bytes, read here as U32 (errata, contract 7).
struct NetworkSettings {
    static constexpr std::uint8_t id = pkt::network_settings;
    static constexpr std::string_view name = "network_settings";
    static constexpr std::size_t min_length = 12;
    static constexpr std::size_t max_length = 15;

    std::uint32_t ip = 0;
    std::uint32_t mask = 0;
    std::uint32_t gateway = 0;
    bool low_delay = false;  // true: Nagle's algorithm off
    std::uint16_t mtu = 0;   // 0 = hardware default

    template <class V>
    void fields(V& v) {
        v.ipv4("ip", ip);
        v.ipv4("mask", mask);
        v.ipv4("gateway", gateway);
        v.optional();
        v.field("low_delay", low_delay, u8);
        v.field("mtu", mtu, u16);
    }
};

enum class StreamType : std::uint8_t {  // StreamType_t
    h264 = 0,
    mjpeg = 1,
    raw = 2,
    yuv = 3,
};
constexpr std::array<EnumName<StreamType>, 4> stream_type_names{{
    {StreamType::h264, "h264"},
    {StreamType::mjpeg, "mjpeg"},
    {StreamType::raw, "raw"},
    {StreamType::yuv, "yuv"},
}};
constexpr std::span<const EnumName<StreamType>> enum_names(StreamType) {
    return stream_type_names;
}

// OrionNetworkVideo / OrionNetworkByteVideo (98): where and how video is streamed. Like 228,
// the two ICD layouts are the same bytes; the address is read as U32.
struct NetworkVideo {
    static constexpr std::uint8_t id = pkt::network_video;
    static constexpr std::string_view name = "network_video";
    static constexpr std::size_t min_length = 6;
    static constexpr std::size_t max_length = 14;

    std::uint32_t dest_ip = 0;
    std::uint16_t port = 0;
    std::uint32_t bitrate = 0;  // bits per second
    std::int8_t ttl = -1;       // <= 0: 64 for unicast, 1 for multicast
    StreamType stream_type = StreamType::h264;
    std::uint8_t mjpeg_quality = 30;  // 10..95
    bool save_settings = false;
    std::uint8_t ts_packet_count = 0;  // TS packets per UDP packet, 0 = no change

    template <class V>
    void fields(V& v) {
        v.ipv4("dest_ip", dest_ip);
        v.field("port", port, u16);
        v.optional();
        v.field("bitrate", bitrate, u32);
        v.field("ttl", ttl, i8);
        v.field("stream_type", stream_type, u8);
        v.field("mjpeg_quality", mjpeg_quality, u8);
        v.bits("save_settings", save_settings, 1);
        v.bits("ts_packet_count", ts_packet_count, 4);
    }
};

inline constexpr std::size_t num_cameras = 2;  // OrionNumberOfCameras_t

enum class CameraType : std::uint8_t {  // OrionCameraType_t
    none = 0,
    visible = 1,
    swir = 2,
    mwir = 3,
    lwir = 4,
};
constexpr std::array<EnumName<CameraType>, 5> camera_type_names{{
    {CameraType::none, "none"},
    {CameraType::visible, "visible"},
    {CameraType::swir, "swir"},
    {CameraType::mwir, "mwir"},
    {CameraType::lwir, "lwir"},
}};
constexpr std::span<const EnumName<CameraType>> enum_names(CameraType) {
    return camera_type_names;
}

enum class CameraProtocol : std::uint8_t {  // OrionCameraProtocol_t
    unknown = 0,
    flir = 1,
    aptina = 2,
    zafiro = 3,
    hitachi = 4,
    bae = 5,
    sony = 6,
    ktnc = 7,
};
constexpr std::array<EnumName<CameraProtocol>, 8> camera_protocol_names{{
    {CameraProtocol::unknown, "unknown"},
    {CameraProtocol::flir, "flir"},
    {CameraProtocol::aptina, "aptina"},
    {CameraProtocol::zafiro, "zafiro"},
    {CameraProtocol::hitachi, "hitachi"},
    {CameraProtocol::bae, "bae"},
    {CameraProtocol::sony, "sony"},
    {CameraProtocol::ktnc, "ktnc"},
}};
constexpr std::span<const EnumName<CameraProtocol>> enum_names(CameraProtocol) {
    return camera_protocol_names;
}

// OrionCamSettings: one camera of OrionCameras.
struct CameraSettings {
    CameraType type = CameraType::none;
    CameraProtocol protocol = CameraProtocol::unknown;
    double min_focal_length_mm = 0;
    double max_focal_length_mm = 0;
    double pixel_pitch_mm = 0;
    std::uint16_t array_width = 0;                    // pixels
    std::uint16_t array_height = 0;                   // pixels
    std::array<double, num_gimbal_axes> align_min{};  // rad, boresight offsets [pan, tilt]
    std::array<double, num_gimbal_axes> align_max{};  // rad

    template <class V>
    void fields(V& v) {
        v.field("type", type, u8);
        v.field("protocol", protocol, u8);
        v.field("min_focal_length_mm", min_focal_length_mm, u32, 1000.0);
        v.field("max_focal_length_mm", max_focal_length_mm, u32, 1000.0);
        v.field("pixel_pitch_mm", pixel_pitch_mm, u16, 1000000.0);
        v.field("array_width", array_width, u16);
        v.field("array_height", array_height, u16);
        v.field("align_min", align_min, i16, 32767.0 / pi, Unit::radians);
        v.field("align_max", align_max, i16, 32767.0 / pi, Unit::radians);
    }
};

// OrionCameras (99): the cameras installed in the gimbal.
struct Cameras {
    static constexpr std::uint8_t id = pkt::cameras;
    static constexpr std::string_view name = "cameras";
    static constexpr std::size_t min_length = 4;
    static constexpr std::size_t max_length = 52;

    std::vector<CameraSettings> cameras;

    template <class V>
    void fields(V& v) {
        v.count("num_cameras", cameras, u8, num_cameras);
        v.reserved(u24);  // 3 x U8
        v.group("cameras", cameras);
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using ConfigPackets =
    PacketList<UartConfig, Limits, InsOptions, NetworkSettings, NetworkVideo, Cameras>;
}  // namespace gimbal::orion
