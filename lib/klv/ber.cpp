#include "klv/ber.hpp"

namespace gimbal::klv {

std::size_t ber_length_size(std::uint64_t length) {
    if (length < 0x80) return 1;
    std::size_t n = 0;
    for (std::uint64_t v = length; v != 0; v >>= 8) ++n;
    return 1 + n;
}

void append_ber_length(Bytes& out, std::uint64_t length) {
    if (length < 0x80) {
        out.push_back(static_cast<std::uint8_t>(length));
        return;
    }
    const std::size_t n = ber_length_size(length) - 1;
    out.push_back(static_cast<std::uint8_t>(0x80 | n));
    for (std::size_t i = n; i-- > 0;) out.push_back(static_cast<std::uint8_t>(length >> (8 * i)));
}

BerRead read_ber_length(std::span<const std::uint8_t> in) {
    if (in.empty()) return {BerStatus::truncated, 0, 0};
    const std::uint8_t first = in[0];
    if (first < 0x80) return {BerStatus::ok, first, 1};
    const std::size_t n = first & 0x7F;
    if (n == 0 || n > max_ber_length_bytes) return {BerStatus::invalid, 0, 0};
    if (in.size() < 1 + n) return {BerStatus::truncated, 0, 0};
    std::uint64_t value = 0;
    for (std::size_t i = 1; i <= n; ++i) value = (value << 8) | in[i];
    return {BerStatus::ok, value, 1 + n};
}

std::size_t ber_oid_size(std::uint64_t value) {
    std::size_t n = 1;
    for (value >>= 7; value != 0; value >>= 7) ++n;
    return n;
}

void append_ber_oid(Bytes& out, std::uint64_t value) {
    const std::size_t n = ber_oid_size(value);
    for (std::size_t i = n; i-- > 0;) {
        const auto group = static_cast<std::uint8_t>((value >> (7 * i)) & 0x7F);
        out.push_back(i == 0 ? group : static_cast<std::uint8_t>(group | 0x80));
    }
}

BerRead read_ber_oid(std::span<const std::uint8_t> in) {
    if (in.empty()) return {BerStatus::truncated, 0, 0};
    if (in[0] == 0x80) return {BerStatus::invalid, 0, 0};
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (i == max_ber_oid_bytes) return {BerStatus::invalid, 0, 0};
        // The tenth byte may only add the 64th bit.
        if (i == max_ber_oid_bytes - 1 && (value >> 57) != 0) return {BerStatus::invalid, 0, 0};
        value = (value << 7) | (in[i] & 0x7Fu);
        if ((in[i] & 0x80) == 0) return {BerStatus::ok, value, i + 1};
    }
    return {BerStatus::truncated, 0, 0};
}

}  // namespace gimbal::klv
