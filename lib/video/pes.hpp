// PES packets (ISO/IEC 13818-1 2.4.3.6): the header fields a relay needs (stream_id,
// length, data alignment, PTS/DTS) and the writer of the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gimbal::video {

namespace stream_id {
inline constexpr std::uint8_t private_stream_1 = 0xBD;  // asynchronous KLV (ST 1402)
inline constexpr std::uint8_t video = 0xE0;
inline constexpr std::uint8_t metadata = 0xFC;  // metadata_stream (synchronous KLV)
}  // namespace stream_id

struct PesHeader {
    std::uint8_t stream_id = 0;
    std::size_t packet_length = 0;  // PES_packet_length: 0 = unbounded (video only)
    bool data_alignment = false;
    std::optional<std::uint64_t> pts;
    std::optional<std::uint64_t> dts;
    std::size_t header_size = 0;  // bytes before the payload
};

// nullopt: no start code prefix, or the header runs past the bytes given.
std::optional<PesHeader> parse_pes_header(std::span<const std::uint8_t> pes);

// Appends a PES header with the optional header (marker bits '10', data_alignment as given,
// PTS and DTS when set; DTS only with PTS). payload_size 0 or above 65535 - header writes
// PES_packet_length 0 (allowed for video only).
void write_pes_header(std::vector<std::uint8_t>& out, std::uint8_t stream_id,
                      std::size_t payload_size, std::optional<std::uint64_t> pts,
                      std::optional<std::uint64_t> dts, bool data_alignment);

}  // namespace gimbal::video
