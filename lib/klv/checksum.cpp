#include "klv/checksum.hpp"

namespace gimbal::klv {

std::uint16_t checksum16(std::span<const std::uint8_t> bytes) {
    std::uint32_t sum = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i)
        sum += (i % 2 == 0) ? static_cast<std::uint32_t>(bytes[i]) << 8 : bytes[i];
    return static_cast<std::uint16_t>(sum);
}

}  // namespace gimbal::klv
