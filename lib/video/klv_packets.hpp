// SMPTE ST 336 KLV framing only (no ST 0601 meaning): 16-byte universal key, BER length
// (short form < 128, or 0x80 | n followed by n bytes). Used to send one local set per
// datagram and to check that a KLV payload is whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::video {

// The whole KLV packets at the front of `bytes` (key + length + value each); `rest` gets
// the bytes after the last whole packet (a cut-off or malformed tail).
std::vector<std::span<const std::uint8_t>> split_klv_packets(
    std::span<const std::uint8_t> bytes, std::span<const std::uint8_t>* rest = nullptr);

}  // namespace gimbal::video
