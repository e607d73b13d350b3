// The Viewpro frame checksum: low 8 bits of the sum of every byte before it.
#pragma once

#include <cstdint>
#include <span>

namespace gimbal::viewpro {

inline std::uint8_t sum8(std::span<const std::uint8_t> bytes) {
    unsigned sum = 0;
    for (const std::uint8_t b : bytes) sum += b;
    return static_cast<std::uint8_t>(sum & 0xFFu);
}

// True when the last byte of `frame` is the checksum of the bytes before it.
inline bool checksum_ok(std::span<const std::uint8_t> frame) {
    return !frame.empty() && sum8(frame.first(frame.size() - 1)) == frame.back();
}

}  // namespace gimbal::viewpro
