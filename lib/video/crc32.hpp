// CRC-32/MPEG-2 (ISO 13818-1 Annex A): polynomial 0x04C11DB7, initial 0xFFFFFFFF, no
// reflection, no final XOR. Every PSI section ends with it; over a whole section including
// its CRC the result is 0.
#pragma once

#include <cstdint>
#include <span>

namespace gimbal::video {

std::uint32_t crc32_mpeg2(std::span<const std::uint8_t> bytes);

}  // namespace gimbal::video
