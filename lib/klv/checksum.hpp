// The checksum of a UAS Datalink Local Set (MISB ST 0601 section 6.6, item 1): a running
// 16-bit sum of the packet read as big-endian 16-bit words, from the first byte of the
// 16-byte key through the checksum item's tag and length byte (an odd byte count sums as if a
// zero byte followed). ST 0601 does not use a CRC here; CRC-16-CCITT is what other MISB sets
// (ST 0903, ST 1601) use. Pure.
#pragma once

#include <cstdint>
#include <span>

namespace gimbal::klv {

std::uint16_t checksum16(std::span<const std::uint8_t> bytes);

}  // namespace gimbal::klv
