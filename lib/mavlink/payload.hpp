// Message fields <-> payload bytes: little-endian, in wire order (largest type first).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "mavlink/messages.hpp"

namespace gimbal::mavlink {

// The longest payload of the messages we know, extensions included (CAMERA_INFORMATION: 237).
inline constexpr std::size_t max_known_length = 255;

// Full-length payload with extensions (no truncation) and how many bytes of `bytes` it fills.
struct PayloadBytes {
    std::array<std::uint8_t, max_known_length> bytes{};
    std::size_t size = 0;
    std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

PayloadBytes encode_payload(const Payload& payload);

// Decodes a payload of message `msgid`. Bytes missing at the end read as zero (MAVLink 2
// truncation); bytes past the known fields (newer extensions) are ignored. nullopt for an
// id this codec does not know.
std::optional<Payload> decode_payload(std::uint32_t msgid, std::span<const std::uint8_t> bytes);

}  // namespace gimbal::mavlink
