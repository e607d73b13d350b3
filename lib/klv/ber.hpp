// BER encodings used by KLV (SMPTE 336, MISB ST 0601 section 6): the length of a value
// (short form 0..127 in one byte, long form 0x80|n followed by n big-endian bytes) and the
// BER-OID integers ST 0601 uses for tags above 127 and in its lists (7 bits a byte, the top
// bit set on every byte but the last). Pure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace gimbal::klv {

using Bytes = std::vector<std::uint8_t>;

enum class BerStatus {
    ok,
    truncated,  // the input ends inside the field
    invalid,    // not a valid encoding (indefinite length, too many bytes, padded OID)
};

struct BerRead {
    BerStatus status = BerStatus::invalid;
    std::uint64_t value = 0;
    std::size_t size = 0;  // bytes the field takes (when ok)
};

// Long-form lengths of more than 8 bytes do not fit a 64-bit size and are refused.
inline constexpr std::size_t max_ber_length_bytes = 8;
// A BER-OID of up to 10 bytes carries 64 bits; longer ones are refused.
inline constexpr std::size_t max_ber_oid_bytes = 10;

// Minimal encoding: short form below 128, else the fewest long-form bytes.
void append_ber_length(Bytes& out, std::uint64_t length);
std::size_t ber_length_size(std::uint64_t length);
// Any valid form: short, or long with 1..8 bytes (leading zero bytes allowed, as SMPTE 336
// writers use fixed 4-byte lengths). 0x80 (indefinite) and 0xFF are invalid.
BerRead read_ber_length(std::span<const std::uint8_t> in);

void append_ber_oid(Bytes& out, std::uint64_t value);
std::size_t ber_oid_size(std::uint64_t value);
// Refuses a leading 0x80 byte (padding, X.690 8.19.2), more than 10 bytes or a value past
// 64 bits, and an input that ends before the last byte.
BerRead read_ber_oid(std::span<const std::uint8_t> in);

}  // namespace gimbal::klv
