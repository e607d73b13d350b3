#include "protocols/orion/codec/framing.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace gimbal::orion {

namespace {

// Adds a block of bytes to the running sums. The reference takes A = 1 + sum(x) and B = the
// sum of the running A; over m bytes that is A' = A + sum(x_i), B' = B + m A + sum((m - i) x_i).
// Eight bytes at a time: split into even and odd bytes in 16-bit lanes, one multiply sums the
// lanes, two more form the weighted sum (the top lane of lanes * (c0, c1, c2, c3) is
// l0 c3 + l1 c2 + l2 c1 + l3 c0; no lane can carry into it).
void fletcher_block(const std::uint8_t* x, std::size_t m, std::uint64_t& a, std::uint64_t& b) {
    std::size_t i = 0;
    if constexpr (std::endian::native == std::endian::little) {
        constexpr std::uint64_t lanes = 0x00FF00FF00FF00FFull;
        constexpr std::uint64_t ones = 0x0001000100010001ull;
        constexpr std::uint64_t even_weights = 0x0008000600040002ull;  // bytes 0 2 4 6: 8 6 4 2
        constexpr std::uint64_t odd_weights = 0x0007000500030001ull;   // bytes 1 3 5 7: 7 5 3 1
        for (; i + 8 <= m; i += 8) {
            std::uint64_t v;
            std::memcpy(&v, x + i, 8);
            const std::uint64_t even = v & lanes;
            const std::uint64_t odd = (v >> 8) & lanes;
            const std::uint64_t sum = ((even + odd) * ones) >> 48;
            const std::uint64_t weighted = (even * even_weights + odd * odd_weights) >> 48;
            b += 8 * a + weighted;
            a += sum;
        }
    }
    for (; i < m; ++i) {
        a += x[i];
        b += a;
    }
}

}  // namespace

std::uint16_t fletcher251(std::span<const std::uint8_t> bytes) {
    // 64-bit sums cannot overflow within a block of 2^20 bytes, and one modulo per block gives
    // the same result as the reference's modulo after every byte. A frame is one block.
    constexpr std::size_t block = std::size_t{1} << 20;
    std::uint64_t a = 1;
    std::uint64_t b = 0;
    for (std::size_t start = 0; start < bytes.size(); start += block) {
        fletcher_block(bytes.data() + start, std::min(block, bytes.size() - start), a, b);
        a %= 251;
        b %= 251;
    }
    return static_cast<std::uint16_t>((a << 8) | b);
}

void append_frame(std::uint8_t id, std::span<const std::uint8_t> data,
                  std::vector<std::uint8_t>& out) {
    const std::size_t start = out.size();
    out.push_back(sync0);
    out.push_back(sync1);
    out.push_back(id);
    out.push_back(static_cast<std::uint8_t>(data.size()));
    out.insert(out.end(), data.begin(), data.end());
    const std::uint16_t sum =
        fletcher251(std::span<const std::uint8_t>(out.data() + start, out.size() - start));
    out.push_back(static_cast<std::uint8_t>(sum >> 8));
    out.push_back(static_cast<std::uint8_t>(sum & 0xFF));
}

std::vector<std::uint8_t> frame_bytes(std::uint8_t id, std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> out;
    out.reserve(header_size + data.size() + checksum_size);
    append_frame(id, data, out);
    return out;
}

}  // namespace gimbal::orion
