// ICD section "Packets for gimbal control".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/fields.hpp"

namespace gimbal::orion {

// The pan/tilt command structure shared by OrionCmd and OrionStartupCmd.
struct PanTiltCmd {
    std::array<double, 2> target{};  // rad (position modes) or rad/s (rate modes)
    Mode mode = Mode::disabled;
    bool stabilized = false;
    double impulse_time_s = 0;

    template <class V>
    void fields(V& v) {
        v.field("target", target, i16, 1000.0, Unit::radians);
        v.field("mode", mode, u8);
        v.field("stabilized", stabilized, u8);
        v.field("impulse_time_s", impulse_time_s, u8, 10.0);
    }
};

// OrionCmd (1): pan/tilt control; the gimbal echoes it back.
struct Cmd {
    static constexpr std::uint8_t id = pkt::cmd;
    static constexpr std::string_view name = "cmd";
    static constexpr std::size_t min_length = 7;
    static constexpr std::size_t max_length = 7;

    PanTiltCmd cmd;

    template <class V>
    void fields(V& v) {
        cmd.fields(v);
    }
};

// OrionStartupCmd (7): the command the gimbal runs when its motors initialize.
struct StartupCmd {
    static constexpr std::uint8_t id = pkt::startup_cmd;
    static constexpr std::string_view name = "startup_cmd";
    static constexpr std::size_t min_length = 7;
    static constexpr std::size_t max_length = 7;

    PanTiltCmd cmd{.target = {}, .mode = Mode::position};  // ICD: position mode, pan/tilt 0

    template <class V>
    void fields(V& v) {
        cmd.fields(v);
    }
};

enum class GeopointOptions : std::uint8_t { none = 0, stare = 1, closure = 2, stare_closure = 3 };
constexpr std::array<EnumName<GeopointOptions>, 4> geopoint_options_names{{
    {GeopointOptions::none, "none"},
    {GeopointOptions::stare, "stare"},
    {GeopointOptions::closure, "closure"},
    {GeopointOptions::stare_closure, "stare_closure"},
}};
constexpr std::span<const EnumName<GeopointOptions>> enum_names(GeopointOptions) {
    return geopoint_options_names;
}

// GeopointCmd (213): look at a point (and follow its velocity).
// The ICD gives a minimum length of 18, the length before joystickRange was added (SDK 1.2),
// while its table does not mark joystickRange optional. We honour the stated minimum: an
// 18-byte packet decodes with joystickRange 0 (no joystick propagation). We always send 21.
struct GeopointCmd {
    static constexpr std::uint8_t id = pkt::geopoint_cmd;
    static constexpr std::string_view name = "geopoint_cmd";
    static constexpr std::size_t min_length = 18;
    static constexpr std::size_t max_length = 21;

    double target_lat = 0;  // rad
    double target_lon = 0;  // rad
    double target_alt = 0;  // m above WGS84
    std::array<double, 3> target_vel_ned{};
    std::uint16_t joystick_range_m = 0;
    GeopointOptions options = GeopointOptions::none;

    template <class V>
    void fields(V& v) {
        v.field("lat", target_lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("lon", target_lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("alt", target_alt, i32, 10000.0);
        v.field("vel_ned", target_vel_ned, i16, 100.0);
        v.optional();  // see above: bytes 18..20 may be absent
        v.field("joystick_range_m", joystick_range_m, u16);
        v.field("options", options, u8);
    }
};

struct PathPoint {
    std::array<double, 3> pos_ecef{};  // m

    template <class V>
    void fields(V& v) {
        v.field("pos_ecef", pos_ecef, i24, 1.0);
    }
};

// OrionPath (215): follow a path of ECEF points, optionally step-staring.
struct Path {
    static constexpr std::uint8_t id = pkt::path;
    static constexpr std::string_view name = "path";
    static constexpr std::size_t min_length = 2;
    static constexpr std::size_t max_length = 140;

    bool point_down = false;
    std::uint8_t num_cross_track_steps = 0;
    std::vector<PathPoint> points;
    double along_track_step_angle = 0;  // rad
    double cross_track_step_ratio = 0;

    template <class V>
    void fields(V& v) {
        v.count("num_points", points, u8, max_path_points);
        v.bits("point_down", point_down, 1);
        v.reserved_bits(3);
        v.bits("num_cross_track_steps", num_cross_track_steps, 4);
        v.group("points", points);
        v.optional();
        v.field("along_track_step_angle", along_track_step_angle, u16, 65535.0 / pi, Unit::radians);
        v.field("cross_track_step_ratio", cross_track_step_ratio, u8, 255.0 / 2.55);
    }
};

// StareAck (218): the step-stare image is taken, the gimbal may move on.
struct StareAck {
    static constexpr std::uint8_t id = pkt::stare_ack;
    static constexpr std::string_view name = "stare_ack";
    static constexpr std::size_t min_length = 4;
    static constexpr std::size_t max_length = 4;

    std::uint32_t echo_system_time_ms = 0;  // systemTime of the StareStart being acknowledged

    template <class V>
    void fields(V& v) {
        v.field("echo_system_time_ms", echo_system_time_ms, u32);
    }
};

// OrionCameraSwitch (96).
struct CameraSwitch {
    static constexpr std::uint8_t id = pkt::camera_switch;
    static constexpr std::string_view name = "camera_switch";
    static constexpr std::size_t min_length = 1;
    static constexpr std::size_t max_length = 1;

    std::uint8_t index = 0;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
    }
};

// OrionCameraState (97): zoom and focus of one camera (to be deprecated by the ICD).
struct CameraState {
    static constexpr std::uint8_t id = pkt::camera_state;
    static constexpr std::string_view name = "camera_state";
    static constexpr std::size_t min_length = 2;
    static constexpr std::size_t max_length = 5;

    double zoom = 0;  // digital zoom ratio
    double focus = -1;
    std::uint8_t index = 0;

    template <class V>
    void fields(V& v) {
        v.field("zoom", zoom, i16, 100.0);
        v.optional();
        v.field("focus", focus, i16, 10000.0);
        v.field("index", index, u8);
    }
};

enum class FlirNucType : std::uint8_t {  // FlirNucType_t
    manual = 0,
    ssn_no_motion = 1,
    ssn_low = 2,
    ssn_medium = 3,
    ssn_high = 4,
};
constexpr std::array<EnumName<FlirNucType>, 5> flir_nuc_type_names{{
    {FlirNucType::manual, "manual"},
    {FlirNucType::ssn_no_motion, "ssn_no_motion"},
    {FlirNucType::ssn_low, "ssn_low"},
    {FlirNucType::ssn_medium, "ssn_medium"},
    {FlirNucType::ssn_high, "ssn_high"},
}};
constexpr std::span<const EnumName<FlirNucType>> enum_names(FlirNucType) {
    return flir_nuc_type_names;
}

// OrionFlirSettings (103).
struct FlirSettings {
    static constexpr std::uint8_t id = pkt::flir_settings;
    static constexpr std::string_view name = "flir_settings";
    static constexpr std::size_t min_length = 5;
    static constexpr std::size_t max_length = 7;

    std::uint8_t index = 0;  // 0xFF: any FLIR camera
    std::uint8_t palette = 0;
    FlirNucType nuc_type = FlirNucType::manual;
    bool black_hot = false;  // ignored when palette is non-zero
    std::uint8_t max_agc_gain = 0;
    std::int8_t ace_level = 0;
    std::uint8_t dde_threshold = 0;
    std::uint8_t agc_midpoint = 128;
    double integration_time_ms = 8;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.reserved_bits(1);
        v.bits("palette", palette, 3);
        v.bits("nuc_type", nuc_type, 3);
        v.bits("black_hot", black_hot, 1);
        v.field("max_agc_gain", max_agc_gain, u8);
        v.field("ace_level", ace_level, i8);
        v.field("dde_threshold", dde_threshold, u8);
        v.optional();
        v.field("agc_midpoint", agc_midpoint, u8);
        v.field("integration_time_ms", integration_time_ms, u8, Scale{255.0 / 29.0, 1.0});
    }
};

// OrionAptinaSettings (104).
struct AptinaSettings {
    static constexpr std::uint8_t id = pkt::aptina_settings;
    static constexpr std::string_view name = "aptina_settings";
    static constexpr std::size_t min_length = 13;
    static constexpr std::size_t max_length = 15;

    std::uint8_t index = 0;  // 0xFF: any Aptina camera
    // The ICD says "microseconds" for MinExposure but scales it exactly like MaxExposure
    // (milliseconds, 0.05..33), as the Sony packet does for both: milliseconds it is.
    double min_exposure_ms = 0.05;
    double max_exposure_ms = 0.05;
    double min_gain = 1;
    double max_gain = 1;
    std::int8_t brightness = 0;
    double contrast = 0;
    double saturation = 0;
    double sharpness = 0;
    bool debug_enable = false;
    std::int8_t hue = 0;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.field("min_exposure_ms", min_exposure_ms, u16, Scale{65535.0 / 32.95, 0.05});
        v.field("max_exposure_ms", max_exposure_ms, u16, Scale{65535.0 / 32.95, 0.05});
        v.field("min_gain", min_gain, u16, Scale{65535.0 / 31.0, 1.0});
        v.field("max_gain", max_gain, u16, Scale{65535.0 / 31.0, 1.0});
        v.field("brightness", brightness, i8);
        v.field("contrast", contrast, i8, 127.0);
        v.field("saturation", saturation, i8, 127.0);
        v.field("sharpness", sharpness, u8, 255.0 / 5.0);
        v.optional();
        v.bits("debug_enable", debug_enable, 1);  // 13:6..13:0 unused; Hue is byte 14
        v.field("hue", hue, i8);
    }
};

// OrionZafiroSettings (105).
struct ZafiroSettings {
    static constexpr std::uint8_t id = pkt::zafiro_settings;
    static constexpr std::string_view name = "zafiro_settings";
    static constexpr std::size_t min_length = 6;
    static constexpr std::size_t max_length = 7;

    std::uint8_t index = 0;  // 0xFF: any Zafiro camera
    bool black_hot = false;
    double integration_time_ms = 1;
    bool lap_enabled = false;
    double lap_gain = 0.5;
    double agc_saturation = 0;
    bool use_nuc_table_presets = false;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.field("black_hot", black_hot, u8);
        v.field("integration_time_ms", integration_time_ms, u8, Scale{255.0 / 29.0, 1.0});
        v.field("lap_enabled", lap_enabled, u8);
        v.field("lap_gain", lap_gain, u8, Scale{255.0 / 3.5, 0.5});
        v.field("agc_saturation", agc_saturation, u8, 255.0 / 0.1);
        v.optional();
        v.field("use_nuc_table_presets", use_nuc_table_presets, u8);
    }
};

// OrionHitachiSettings (106).
struct HitachiSettings {
    static constexpr std::uint8_t id = pkt::hitachi_settings;
    static constexpr std::string_view name = "hitachi_settings";
    static constexpr std::size_t min_length = 5;
    static constexpr std::size_t max_length = 6;

    std::uint8_t index = 0;                // 0xFF: any Hitachi camera
    std::int16_t integration_time_us = 0;  // negative: shutter priority off
    double aperture = 0;                   // f-number; negative: aperture priority off
    double sharpness = 1;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.field("integration_time_us", integration_time_us, i16);
        v.field("aperture", aperture, i16, 10.0);
        v.optional();
        v.field("sharpness", sharpness, u8, 255.0 / 5.0);
    }
};

// OrionSonySettings (108).
struct SonySettings {
    static constexpr std::uint8_t id = pkt::sony_settings;
    static constexpr std::string_view name = "sony_settings";
    static constexpr std::size_t min_length = 12;
    static constexpr std::size_t max_length = 12;

    std::uint8_t index = 0;  // 0xFF: any Sony camera
    double min_exposure_ms = 0.05;
    double max_exposure_ms = 0.05;
    std::uint8_t min_gain_db = 0;
    std::uint8_t max_gain_db = 0;
    std::uint8_t brightness = 0;
    double contrast = 0;
    double saturation = 0;
    double sharpness = 0;
    double frame_rate_hz = 0;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.field("min_exposure_ms", min_exposure_ms, u16, Scale{65535.0 / 32.95, 0.05});
        v.field("max_exposure_ms", max_exposure_ms, u16, Scale{65535.0 / 32.95, 0.05});
        v.field("min_gain_db", min_gain_db, u8);
        v.field("max_gain_db", max_gain_db, u8);
        v.field("brightness", brightness, u8);
        v.field("contrast", contrast, i8, 127.0);
        v.field("saturation", saturation, i8, 127.0);
        v.field("sharpness", sharpness, u8, 255.0 / 5.0);
        v.field("frame_rate_hz", frame_rate_hz, u8, 255.0 / 30.0);
    }
};

// OrionKtncSettings (109).
struct KtncSettings {
    static constexpr std::uint8_t id = pkt::ktnc_settings;
    static constexpr std::string_view name = "ktnc_settings";
    static constexpr std::size_t min_length = 5;
    static constexpr std::size_t max_length = 11;

    std::uint8_t index = 0;                // 0xFF: any KTnC camera
    std::int16_t integration_time_us = 0;  // negative: shutter priority off
    double aperture = 0;                   // f-number; negative: aperture priority off
    double sharpness = 8;
    bool vertical_flip = false;
    double exposure_comp = 7;
    double contrast = 8;
    double saturation = 14;
    bool night_mode = false;
    bool reset_to_defaults = false;

    template <class V>
    void fields(V& v) {
        v.field("index", index, u8);
        v.field("integration_time_us", integration_time_us, i16);
        v.field("aperture", aperture, i16, 10.0);
        v.optional();
        v.field("sharpness", sharpness, u8, 255.0 / 16.0);
        v.field("vertical_flip", vertical_flip, u8);
        v.field("exposure_comp", exposure_comp, u8, 255.0 / 14.0);
        v.field("contrast", contrast, u8, 255.0 / 32.0);
        v.field("saturation", saturation, u8, 255.0 / 32.0);
        v.bits("night_mode", night_mode, 1);
        v.bits("reset_to_defaults", reset_to_defaults, 1);
    }
};

// OrionRetractCommand (160). (RetractCmd is the OrionRetractCmd_t enumeration.)
struct RetractCommand {
    static constexpr std::uint8_t id = pkt::retract_cmd;
    static constexpr std::string_view name = "retract_cmd";
    static constexpr std::size_t min_length = 2;
    static constexpr std::size_t max_length = 2;

    RetractCmd cmd = RetractCmd::disable;

    template <class V>
    void fields(V& v) {
        v.field("cmd", cmd, u8);
        v.reserved(u8);
    }
};

// OrionUserData (178): opaque bytes to or from a gimbal communication port.
struct UserData {
    static constexpr std::uint8_t id = pkt::user_data;
    static constexpr std::string_view name = "user_data";
    static constexpr std::size_t min_length = 6;
    static constexpr std::size_t max_length = 134;
    static constexpr std::size_t max_data = 128;

    UserDataPort port = UserDataPort::ethernet;
    std::uint32_t block_id = 0;  // user-defined identifier or sequence number
    std::vector<std::uint8_t> data;

    template <class V>
    void fields(V& v) {
        v.field("port", port, u8);
        v.count("size", data, u8, max_data);  // counts `data`, two fields later
        v.field("id", block_id, u32);
        v.field("data", data, u8);
    }
};

// OrionLaserCommand (3). The password is a variable-length string: it moves every later field.
struct LaserCmd {
    static constexpr std::uint8_t id = pkt::laser_cmd;
    static constexpr std::string_view name = "laser_cmd";
    static constexpr std::size_t min_length = 11;
    static constexpr std::size_t max_length = 29;

    std::uint8_t index = 0;
    std::string password;
    bool enable = false;
    bool arm = false;
    bool fire = false;
    std::uint16_t on_time_ms = 0;
    std::uint16_t off_time_ms = 0;
    std::uint16_t prf_code = 0;
    bool safety_bypass = false;

    template <class V>
    void fields(V& v) {
        v.reserved(u16);
        v.field("index", index, u8);
        v.string("password", password, 16);
        v.field("enable", enable, u8);
        v.field("arm", arm, u8);
        v.field("fire", fire, u8);
        v.field("on_time_ms", on_time_ms, u16);
        v.field("off_time_ms", off_time_ms, u16);
        v.optional();
        v.field("prf_code", prf_code, u16);
        v.field("safety_bypass", safety_bypass, u8);
    }
};

// One laser of OrionLaserStates.
struct LaserState {
    LaserType type = LaserType::none;
    bool enabled = false;
    bool armed = false;
    bool active = false;
    bool ground_speed_lock = false;
    bool altitude_lock = false;
    bool password_lock = false;
    bool ap_comm_lock = false;
    bool ap_flying_lock = false;
    bool bypass_enabled = false;
    bool pitch_angle_lock = false;
    std::uint16_t wait_timer_ms = 0;

    template <class V>
    void fields(V& v) {
        v.field("type", type, u8);
        v.bits("enabled", enabled, 1);
        v.bits("armed", armed, 1);
        v.bits("active", active, 1);
        v.bits("ground_speed_lock", ground_speed_lock, 1);
        v.bits("altitude_lock", altitude_lock, 1);
        v.bits("password_lock", password_lock, 1);
        v.bits("ap_comm_lock", ap_comm_lock, 1);
        v.bits("ap_flying_lock", ap_flying_lock, 1);
        v.bits("bypass_enabled", bypass_enabled, 1);
        v.bits("pitch_angle_lock", pitch_angle_lock, 1);
        v.reserved_bits(14);  // 3:5...4:0
        v.field("wait_timer_ms", wait_timer_ms, u16);
    }
};

// OrionLaserStates (6): state of each installed laser.
struct LaserStates {
    static constexpr std::uint8_t id = pkt::laser_states;
    static constexpr std::string_view name = "laser_states";
    static constexpr std::size_t min_length = 1;
    static constexpr std::size_t max_length = 13;

    std::vector<LaserState> states;

    template <class V>
    void fields(V& v) {
        v.count("num_lasers", states, u8, max_lasers);
        v.group("states", states);
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using ControlPackets =
    PacketList<Cmd, StartupCmd, GeopointCmd, Path, StareAck, CameraSwitch, CameraState,
               FlirSettings, AptinaSettings, ZafiroSettings, HitachiSettings, SonySettings,
               KtncSettings, RetractCommand, UserData, LaserCmd, LaserStates>;
}  // namespace gimbal::orion
