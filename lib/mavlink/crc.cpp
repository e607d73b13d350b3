#include "mavlink/crc.hpp"

namespace gimbal::mavlink {

std::uint16_t crc16_mcrf4xx(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
    for (const std::uint8_t b : bytes) crc = crc16_mcrf4xx_byte(b, crc);
    return crc;
}

}  // namespace gimbal::mavlink
