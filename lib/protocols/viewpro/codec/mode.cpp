#include "protocols/viewpro/codec/mode.hpp"

namespace gimbal::viewpro {

namespace {

// Mode byte bit layout (ICD section 1).
constexpr std::uint8_t osd_bit = 0x01;
constexpr std::uint8_t network_bit = 0x08;
constexpr std::uint8_t serial_bit = 0x10;
constexpr unsigned format_shift = 5;

Command5 command(std::uint8_t id, std::uint8_t value) {
    return {command_header0, command_header1, id, value, command_end};
}

}  // namespace

std::string_view to_string(OutFormat f) {
    switch (f) {
        case OutFormat::out1:
            return "out1";
        case OutFormat::out2:
            return "out2";
        case OutFormat::out3:
            return "out3";
        case OutFormat::out4:
            return "out4";
    }
    return "out?";
}

std::string_view to_string(Osd o) {
    return o == Osd::uav ? "uav" : "target";
}

std::optional<OutFormat> parse_out_format(std::string_view s) {
    for (const OutFormat f : {OutFormat::out1, OutFormat::out2, OutFormat::out3, OutFormat::out4})
        if (s == to_string(f)) return f;
    return std::nullopt;
}

std::optional<Osd> parse_osd(std::string_view s) {
    if (s == "uav") return Osd::uav;
    if (s == "target") return Osd::target;
    return std::nullopt;
}

std::uint8_t mode_byte(const Mode& m) {
    unsigned b = static_cast<unsigned>(m.format) << format_shift;
    if (m.osd == Osd::target) b |= osd_bit;
    if (m.network) b |= network_bit;
    if (m.serial) b |= serial_bit;
    return static_cast<std::uint8_t>(b);
}

Command5 encode_mode(const Mode& m) {
    return command(set_mode_id, mode_byte(m));
}

Mode decode_mode_byte(std::uint8_t b) {
    Mode m;
    m.osd = (b & osd_bit) != 0 ? Osd::target : Osd::uav;
    m.network = (b & network_bit) != 0;
    m.serial = (b & serial_bit) != 0;
    m.format = static_cast<OutFormat>((b >> format_shift) & 0x03u);
    return m;
}

bool mode_byte_is_defined(std::uint8_t b) {
    return (b >> format_shift) <= 3;
}

Command5 encode_yaw_shift(std::int8_t hundredths_deg) {
    return command(yaw_shift_id, static_cast<std::uint8_t>(hundredths_deg));
}

Command5 encode_pitch_shift(std::int8_t hundredths_deg) {
    return command(pitch_shift_id, static_cast<std::uint8_t>(hundredths_deg));
}

}  // namespace gimbal::viewpro
