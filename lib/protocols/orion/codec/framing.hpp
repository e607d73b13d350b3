// OrionPublic packet framing: D0 0D, id, length (0..140), data, Fletcher-16 mod 251.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "protocols/orion/codec/codec.hpp"

namespace gimbal::orion {

inline constexpr std::uint8_t sync0 = 0xD0;
inline constexpr std::uint8_t sync1 = 0x0D;
inline constexpr std::size_t header_size = 4;
inline constexpr std::size_t checksum_size = 2;
inline constexpr std::size_t max_frame_size = header_size + max_data_length + checksum_size;

// Checksum over `bytes` (sync through last data byte): A in the high byte, B in the low byte.
std::uint16_t fletcher251(std::span<const std::uint8_t> bytes);

// One checksum-valid packet as it came off (or goes onto) the wire.
struct Frame {
    std::uint8_t id = 0;
    Payload payload;
    std::span<const std::uint8_t> data() const { return payload.view(); }
};

// Appends the full wire form of a packet (header, data, checksum) to `out`.
void append_frame(std::uint8_t id, std::span<const std::uint8_t> data,
                  std::vector<std::uint8_t>& out);
std::vector<std::uint8_t> frame_bytes(std::uint8_t id, std::span<const std::uint8_t> data);

// Wire bytes of a typed packet.
template <class P>
std::vector<std::uint8_t> to_wire(const P& packet) {
    const Payload p = encode(packet);
    return frame_bytes(P::id, p.view());
}

// A zero-length packet: how a client asks the gimbal to send that packet.
inline std::vector<std::uint8_t> request_bytes(std::uint8_t id) {
    return frame_bytes(id, {});
}

}  // namespace gimbal::orion
