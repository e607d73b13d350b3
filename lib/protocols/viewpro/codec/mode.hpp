// Viewpro target-GPS protocol, section 1 and 5: the 5-byte commands `AA 55 ID XX FF`.
// The mode command selects what the gimbal shows on its OSD and which OUTx frame it sends
// where; the shift commands nudge the calculated target point by 0.01 degree steps.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace gimbal::viewpro {

enum class Osd : std::uint8_t { uav = 0, target = 1 };
enum class OutFormat : std::uint8_t { out1, out2, out3, out4 };

std::string_view to_string(OutFormat);  // "out1".."out4"
std::string_view to_string(Osd);        // "uav", "target"
std::optional<OutFormat> parse_out_format(std::string_view);
std::optional<Osd> parse_osd(std::string_view);

// The mode byte's bit fields. Defaults are what gimbald sends when the configuration is
// silent (target on OSD, OUT3 on the serial port); the gimbal's own default is
// gimbal_default_mode_byte.
struct Mode {
    Osd osd = Osd::target;
    bool network = false;
    bool serial = true;
    OutFormat format = OutFormat::out3;
    friend bool operator==(const Mode&, const Mode&) = default;
};

inline constexpr std::uint8_t command_header0 = 0xAA;
inline constexpr std::uint8_t command_header1 = 0x55;
inline constexpr std::uint8_t command_end = 0xFF;
inline constexpr std::uint8_t set_mode_id = 0x0F;
inline constexpr std::uint8_t yaw_shift_id = 0x06;
inline constexpr std::uint8_t pitch_shift_id = 0x36;
inline constexpr std::size_t command_size = 5;
// ICD example 1.6: target on OSD, no output anywhere.
inline constexpr std::uint8_t gimbal_default_mode_byte = 0x01;
// Largest shift step the ICD's examples use (1.00 degree); the daemon splits bigger shifts.
inline constexpr std::int8_t max_shift_step = 100;

using Command5 = std::array<std::uint8_t, command_size>;

std::uint8_t mode_byte(const Mode&);
Command5 encode_mode(const Mode&);
// Reserved bits 1..2 are ignored. Format values 4..7 are undefined in the ICD; only bits 5..6
// are read, so they alias out1..out4 (use mode_byte_is_defined() to tell).
Mode decode_mode_byte(std::uint8_t mode_byte);
bool mode_byte_is_defined(std::uint8_t mode_byte);  // format bits 5..7 are 0..3

Command5 encode_yaw_shift(std::int8_t hundredths_deg);    // AA 55 06 XX FF
Command5 encode_pitch_shift(std::int8_t hundredths_deg);  // AA 55 36 XX FF

}  // namespace gimbal::viewpro
