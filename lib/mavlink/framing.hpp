// MAVLink wire frames.
//   v1: FE len seq sysid compid msgid                         payload crc_lo crc_hi
//   v2: FD len incompat compat seq sysid compid msgid(3, LE)  payload crc_lo crc_hi [signature]
// The CRC (CRC-16/MCRF4XX) covers everything after the magic byte plus the message's
// CRC_EXTRA. A v2 payload may be truncated (trailing zero bytes left out); a v2 frame with
// incompat flag 0x01 is followed by a 13-byte signature.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mavlink/messages.hpp"

namespace gimbal::mavlink {

inline constexpr std::uint8_t magic_v1 = 0xFE;
inline constexpr std::uint8_t magic_v2 = 0xFD;
inline constexpr std::size_t header_size_v1 = 6;
inline constexpr std::size_t header_size_v2 = 10;
inline constexpr std::size_t checksum_size = 2;
inline constexpr std::size_t signature_size = 13;
inline constexpr std::size_t max_payload_length = 255;
inline constexpr std::uint8_t incompat_signed = 0x01;  // the only incompat flag defined
inline constexpr std::size_t max_frame_size =
    header_size_v2 + max_payload_length + checksum_size + signature_size;

// Checksum of a frame: `covered` is the frame from the length byte through the payload.
std::uint16_t frame_crc(std::span<const std::uint8_t> covered, std::uint8_t crc_extra);

std::vector<std::uint8_t> encode_v1(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq);
// Unsigned, with trailing zero bytes of the payload left out (at least one byte is kept).
std::vector<std::uint8_t> encode_v2(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq);
// The same with incompat flag 0x01 set (and in the CRC) when `signed_flag`, ready for
// append_signature() (signing.hpp) to add the 13 signature bytes.
std::vector<std::uint8_t> encode_v2(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq, bool signed_flag);

}  // namespace gimbal::mavlink
