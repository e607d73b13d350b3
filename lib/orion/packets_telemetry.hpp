// ICD section "Packets sent regularly by the gimbal".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "orion/enums.hpp"
#include "orion/fields.hpp"

namespace gimbal::orion {

enum class InsRotation : std::uint8_t { gimbal_native = 0, platform = 1, payload_ball = 2 };
constexpr std::array<EnumName<InsRotation>, 3> ins_rotation_names{{
    {InsRotation::gimbal_native, "in_gimbal_native"},
    {InsRotation::platform, "in_platform"},
    {InsRotation::payload_ball, "in_payload_ball"},
}};
constexpr std::span<const EnumName<InsRotation>> enum_names(InsRotation) {
    return ins_rotation_names;
}

// GeolocateTelemetryCore (212), 10 Hz: where the gimbal is and where it looks.
struct GeolocateTelemetry {
    static constexpr std::uint8_t id = pkt::geolocate_telemetry;
    static constexpr std::string_view name = "geolocate_telemetry";
    static constexpr std::size_t min_length = 46;
    static constexpr std::size_t max_length = 89;

    std::uint32_t system_time_ms = 0;
    std::uint32_t gps_itow_ms = 0;
    std::uint16_t gps_week = 0;
    double geoid_undulation = 0;  // m
    double lat = 0;               // rad
    double lon = 0;               // rad
    double alt = 0;               // m above WGS84
    std::array<double, 3> vel_ned{};
    std::array<double, 4> quat{};      // gimbal mount -> NED, [w x y z]
    double pan = 0;                    // rad
    double tilt = 0;                   // rad
    double hfov = 0;                   // rad
    double vfov = 0;                   // rad
    std::array<double, 3> los_ecef{};  // m
    std::uint16_t pixel_width = 0;
    std::uint16_t pixel_height = 0;
    Mode mode = Mode::unknown;
    double path_progress = 0;
    double stare_time_s = 0;
    std::uint8_t path_from = 0;
    std::uint8_t path_to = 0;
    std::array<double, 2> image_shifts{};  // rad
    double image_shift_delta_time_s = 0;
    double image_shift_confidence = 0;
    std::array<double, 2> output_shifts{};  // rad
    RangeSource range_source = RangeSource::skylink;
    std::uint8_t leap_seconds = 18;
    double pan_alignment = 0;   // rad
    double tilt_alignment = 0;  // rad
    InsRotation ins_rotation_option = InsRotation::gimbal_native;
    std::array<double, 4> ins_quat{};

    template <class V>
    void fields(V& v) {
        v.field("system_time_ms", system_time_ms, u32);
        v.field("gps_itow_ms", gps_itow_ms, u32);
        v.field("gps_week", gps_week, u16);
        v.field("geoid_undulation", geoid_undulation, i16, 32767.0 / 120.0);
        v.field("lat", lat, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("lon", lon, i32, 180.0 * 10000000.0 / pi, Unit::radians);
        v.field("alt", alt, i32, 10000.0);
        v.field("vel_ned", vel_ned, i16, 100.0);
        v.field("quat", quat, i16, 32767.0);
        v.field("pan", pan, i16, 32767.0 / pi, Unit::radians);
        v.field("tilt", tilt, i16, 32767.0 / pi, Unit::radians);
        v.field("hfov", hfov, u16, 65535.0 / (2.0 * pi), Unit::radians);
        v.field("vfov", vfov, u16, 65535.0 / (2.0 * pi), Unit::radians);
        v.optional();
        v.field("los_ecef", los_ecef, i16, 1.0);
        v.field("pixel_width", pixel_width, u16);
        v.field("pixel_height", pixel_height, u16);
        v.field("mode", mode, u8);
        v.field("path_progress", path_progress, u8, 255.0);
        v.field("stare_time_s", stare_time_s, u8, 255.0 / 2.55);
        v.field("path_from", path_from, u8);
        v.field("path_to", path_to, u8);
        v.field("image_shifts", image_shifts, i32, 1000000.0, Unit::radians);
        v.field("image_shift_delta_time_s", image_shift_delta_time_s, u16, 1000.0);
        v.field("image_shift_confidence", image_shift_confidence, u8, 255.0);
        v.field("output_shifts", output_shifts, i16, 32767.0 / pi, Unit::radians);
        v.field("range_source", range_source, u8);
        v.field("leap_seconds", leap_seconds, u8);
        v.field("pan_alignment", pan_alignment, i8, 1000.0, Unit::radians);
        v.field("tilt_alignment", tilt_alignment, i8, 1000.0, Unit::radians);
        v.field("ins_rotation_option", ins_rotation_option, u8);
        if (ins_rotation_option != InsRotation::gimbal_native)
            v.field("ins_quat", ins_quat, i16, 32767.0);
    }
};

}  // namespace gimbal::orion

namespace gimbal::orion {
using TelemetryPackets = PacketList<GeolocateTelemetry>;
}  // namespace gimbal::orion
