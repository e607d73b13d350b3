// The frame check of SIYI's SDK protocol: CRC-16 with polynomial x^16 + x^12 + x^5 + 1
// (0x1021), initial value 0, no reflection, no final XOR - the variant catalogued as
// CRC-16/XMODEM. SIYI's SDK document (chapter "CRC16 Checksum") gives the table-driven form
// with crc_init 0; its example frames (chapter "Communication Data Example") pin it, and
// tests/unit/siyi/test_crc16.cpp checks them. Computed over every byte before the CRC,
// from the first STX byte on; sent low byte first.
#pragma once

#include <cstdint>
#include <span>

namespace gimbal::siyi {

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t init = 0);

}  // namespace gimbal::siyi
