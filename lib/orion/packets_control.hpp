// ICD section "Packets for gimbal control".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "orion/enums.hpp"
#include "orion/fields.hpp"

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
        v.field("joystick_range_m", joystick_range_m, u16);
        v.optional();
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

}  // namespace gimbal::orion

namespace gimbal::orion {
using ControlPackets = PacketList<Cmd, GeopointCmd, Path, LaserCmd>;
}  // namespace gimbal::orion
