// Viewpro section 4.1: the frames a controller sends to the gimbal (vehicle attitude and
// position) - IN1 (34 bytes), IN2 (40 bytes, with velocity) and IN3 (40 bytes, test frame
// with a laser distance; byte 3 = 0xFF tells it from IN2). All little-endian, checksum = sum
// of all previous bytes mod 256. Struct members hold contract units (degrees, metres, m/s).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/time.hpp"

namespace gimbal::viewpro {

inline constexpr std::uint8_t input_header = 0xF9;
inline constexpr std::uint8_t in1_id = 0xFB;
inline constexpr std::uint8_t in2_id = 0xFC;  // also IN3, with byte 3 = in3_flag
inline constexpr std::uint8_t in3_flag = 0xFF;
inline constexpr std::size_t in1_size = 34;
inline constexpr std::size_t in2_size = 40;
inline constexpr std::size_t in3_size = 40;
inline constexpr std::size_t max_input_frame_size = 40;

struct VehicleInput {  // IN1 (no velocity) / IN2 (with velocity)
    DateTime time;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;   // the wire is float radians
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;    // wire: degE7, mm
    std::optional<std::array<double, 3>> vel_ned_mps;  // present -> IN2 (wire: cm/s int16)
};

struct In3 {
    DateTime time;                                 // the wire carries year - 2000 in one byte
    double lrf_m = 0, pitch_deg = 0, yaw_deg = 0;  // wire: mm (uint32), degE3
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    std::array<double, 3> vel_ned_mps{};
};

// Scaled fields are rounded half away from zero and saturated at the field's limits.
std::vector<std::uint8_t> encode_vehicle(const VehicleInput&);  // 34 bytes (IN1) or 40 (IN2)
std::array<std::uint8_t, in3_size> encode_in3(const In3&);

// One complete frame the simulator received from the controller.
struct InputFrame {
    enum class Kind : std::uint8_t { mode, yaw_shift, pitch_shift, in1, in2, in3 };
    Kind kind = Kind::mode;
    std::array<std::uint8_t, max_input_frame_size> bytes{};
    std::size_t size = 0;
    std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};
std::string_view to_string(InputFrame::Kind);  // "mode", "yaw_shift", ..., "in3"

// Checks header, id, length, flag and checksum (or the FF end of a command); nullopt if the
// bytes are not exactly one valid input frame.
std::optional<InputFrame> make_input_frame(std::span<const std::uint8_t> bytes);

// nullopt when the frame is of another kind or malformed.
std::optional<VehicleInput> decode_vehicle(const InputFrame&);  // in1 or in2
std::optional<In3> decode_in3(const InputFrame&);
std::optional<Mode> decode_mode(const InputFrame&);
std::optional<std::int8_t> decode_shift(const InputFrame&);  // yaw_shift or pitch_shift

}  // namespace gimbal::viewpro
