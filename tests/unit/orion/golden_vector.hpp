// One golden byte vector: the data bytes of a packet (without header and checksum).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string_view>
#include <vector>

#include "protocols/orion/codec/enums.hpp"

namespace gimbal::orion::golden_vectors {

using Bytes = std::vector<std::uint8_t>;

struct GoldenVector {
    std::uint8_t id;
    std::string_view name;
    const Bytes* data;
};

// An ICD "zero terminated string of exactly n bytes": the ASCII text, then zeros.
inline Bytes text(std::string_view s, std::size_t n) {
    Bytes out(s.begin(), s.end());
    out.resize(n, 0);
    return out;
}

inline Bytes join(std::initializer_list<Bytes> parts) {
    Bytes out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

}  // namespace gimbal::orion::golden_vectors
