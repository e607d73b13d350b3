#include "video/klv_packets.hpp"

#include <cstdint>

namespace gimbal::video {

std::vector<std::span<const std::uint8_t>> split_klv_packets(std::span<const std::uint8_t> bytes,
                                                             std::span<const std::uint8_t>* rest) {
    std::vector<std::span<const std::uint8_t>> out;
    std::size_t at = 0;
    while (bytes.size() - at > 16) {
        std::size_t pos = at + 16;
        std::size_t length = bytes[pos++];
        if (length & 0x80) {
            const std::size_t n = length & 0x7F;
            // Lengths above 2^32 cannot be whole in memory here; 0x80 alone is indefinite.
            if (n == 0 || n > 4 || pos + n > bytes.size()) break;
            length = 0;
            for (std::size_t i = 0; i < n; ++i) length = (length << 8) | bytes[pos++];
        }
        if (length > bytes.size() - pos) break;
        out.push_back(bytes.subspan(at, pos + length - at));
        at = pos + length;
    }
    if (rest) *rest = bytes.subspan(at);
    return out;
}

}  // namespace gimbal::video
