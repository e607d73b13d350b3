#include "orion/framing.hpp"

namespace gimbal::orion {

std::uint16_t fletcher251(std::span<const std::uint8_t> bytes) {
    // A = 1 + sum(bytes), B = sum of the running A values, both mod 251. A frame is at most
    // 146 bytes, so the sums fit in 32 bits and one modulo at the end gives the same result
    // as the reference's modulo after every byte.
    std::uint32_t a = 1;
    std::uint32_t b = 0;
    for (const std::uint8_t byte : bytes) {
        a += byte;
        b += a;
    }
    return static_cast<std::uint16_t>(((a % 251u) << 8) | (b % 251u));
}

void append_frame(std::uint8_t id, std::span<const std::uint8_t> data,
                  std::vector<std::uint8_t>& out) {
    const std::size_t start = out.size();
    out.push_back(sync0);
    out.push_back(sync1);
    out.push_back(id);
    out.push_back(static_cast<std::uint8_t>(data.size()));
    out.insert(out.end(), data.begin(), data.end());
    const std::uint16_t sum =
        fletcher251(std::span<const std::uint8_t>(out.data() + start, out.size() - start));
    out.push_back(static_cast<std::uint8_t>(sum >> 8));
    out.push_back(static_cast<std::uint8_t>(sum & 0xFF));
}

std::vector<std::uint8_t> frame_bytes(std::uint8_t id, std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> out;
    out.reserve(header_size + data.size() + checksum_size);
    append_frame(id, data, out);
    return out;
}

}  // namespace gimbal::orion
