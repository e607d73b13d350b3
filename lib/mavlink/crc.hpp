// CRC-16/MCRF4XX (the "X.25" checksum of the MAVLink spec): poly 0x1021 reflected, init 0xFFFF,
// no final XOR. Check value: "123456789" -> 0x6F91.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace gimbal::mavlink {

// Continues `crc` over `bytes`; pass a previous result to checksum a message in pieces.
std::uint16_t crc16_mcrf4xx(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0xFFFF);

// One byte at a time, for the CRC_EXTRA byte that is added after the frame.
constexpr std::uint16_t crc16_mcrf4xx_byte(std::uint8_t byte, std::uint16_t crc) {
    std::uint8_t tmp = static_cast<std::uint8_t>(byte ^ (crc & 0xFF));
    tmp = static_cast<std::uint8_t>(tmp ^ (tmp << 4));
    return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

// Text form, as mavgen checksums message definitions to make CRC_EXTRA.
constexpr std::uint16_t crc16_mcrf4xx(std::string_view text, std::uint16_t crc = 0xFFFF) {
    for (const char c : text) crc = crc16_mcrf4xx_byte(static_cast<std::uint8_t>(c), crc);
    return crc;
}

}  // namespace gimbal::mavlink
