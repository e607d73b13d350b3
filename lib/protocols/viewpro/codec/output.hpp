// Viewpro section 4.2: the frames the gimbal sends - OUT1 (23 bytes, id FB), OUT2 (76, FC),
// OUT3 (60, FD) and OUT4 (60, FD with byte 3 = 0xFF). Header FE, little-endian, checksum =
// sum of all previous bytes mod 256. Output holds contract units: degrees, metres.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/time.hpp"

namespace gimbal::viewpro {

inline constexpr std::uint8_t output_header = 0xFE;
inline constexpr std::uint8_t out1_id = 0xFB;
inline constexpr std::uint8_t out2_id = 0xFC;
inline constexpr std::uint8_t out3_id = 0xFD;  // also OUT4, with byte 3 = out4_flag
inline constexpr std::uint8_t out4_flag = 0xFF;
inline constexpr std::size_t out1_size = 23;
inline constexpr std::size_t out2_size = 76;
inline constexpr std::size_t out3_size = 60;
inline constexpr std::size_t out4_size = 60;
inline constexpr std::size_t max_output_frame_size = 76;

std::uint8_t output_id(OutFormat);
std::size_t output_size(OutFormat);

// Gimbal output, decoded into contract units; fields a format lacks stay nullopt.
struct Output {
    OutFormat format = OutFormat::out1;
    std::optional<DateTime> time;
    std::optional<std::uint16_t> zoom;
    std::optional<double> gimbal_roll_deg, gimbal_pitch_deg, gimbal_yaw_deg, lrf_m;
    std::optional<double> uav_roll_deg, uav_pitch_deg, uav_yaw_deg, uav_lat_deg, uav_lon_deg,
        uav_alt_msl_m;
    std::optional<double> target_lat_deg, target_lon_deg, target_alt_msl_m;
};

// One complete, checksum-valid frame from the gimbal.
struct OutputFrame {
    OutFormat format = OutFormat::out1;
    std::array<std::uint8_t, max_output_frame_size> bytes{};
    std::size_t size = 0;
    std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

// Checks header, id, length and checksum; tells OUT3 from OUT4. nullopt if the bytes are
// not exactly one valid output frame.
std::optional<OutputFrame> make_output_frame(std::span<const std::uint8_t> bytes);

std::optional<Output> decode_output(const OutputFrame&);  // nullopt only if malformed
// Uses output.format; missing fields encode as 0. Scaled fields round half away from zero
// and saturate.
std::vector<std::uint8_t> encode_output(const Output&);

}  // namespace gimbal::viewpro
