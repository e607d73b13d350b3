// MPEG-2 transport stream packets (ISO/IEC 13818-1 2.4.3.2 - 2.4.3.5): the 4-byte header,
// the adaptation field (discontinuity, random access, PCR) and the payload.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace gimbal::video {

inline constexpr std::size_t ts_packet_size = 188;
inline constexpr std::uint8_t ts_sync_byte = 0x47;
inline constexpr std::uint16_t pat_pid = 0x0000;
inline constexpr std::uint16_t null_pid = 0x1FFF;
inline constexpr std::uint64_t pcr_hz = 27'000'000;

// stream_type values (13818-1 Table 2-34 and its amendments).
namespace stream_type {
inline constexpr std::uint8_t private_pes = 0x06;  // PES private data (KLVA per ST 1402)
inline constexpr std::uint8_t metadata = 0x15;     // metadata in PES (synchronous KLV)
inline constexpr std::uint8_t h264 = 0x1B;
inline constexpr std::uint8_t h265 = 0x24;
}  // namespace stream_type

struct TsPacket {
    bool transport_error = false;
    bool payload_unit_start = false;
    std::uint16_t pid = 0;
    std::uint8_t scrambling = 0;
    std::uint8_t continuity_counter = 0;
    bool has_payload = false;
    // Adaptation field.
    bool discontinuity = false;
    bool random_access = false;
    std::optional<std::uint64_t> pcr;  // 27 MHz: base * 300 + extension
    // Stuffing bytes after the adaptation field's own fields: in a packet carrying PES
    // data they are only allowed when the PES packet ends here (2.4.3.5, 2.4.3.4).
    bool stuffed = false;
    std::span<const std::uint8_t> payload;
};

// Parses one 188-byte packet (the first byte must be the sync byte); nullopt when the
// adaptation field's length runs past the packet.
std::optional<TsPacket> parse_ts_packet(std::span<const std::uint8_t> packet);

}  // namespace gimbal::video
