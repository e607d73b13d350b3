// Hex text of bytes, the one encoder behind MACs (lower case, contract section 10), the
// simulator's rx log and KLV dumps (upper case, as MISB documents print them).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace gimbal::framing {

enum class HexCase { lower, upper };

inline std::string to_hex(std::span<const std::uint8_t> bytes, HexCase letters = HexCase::lower) {
    const char* digits = letters == HexCase::lower ? "0123456789abcdef" : "0123456789ABCDEF";
    std::string out;
    out.reserve(bytes.size() * 2);
    for (const std::uint8_t b : bytes) {
        out.push_back(digits[b >> 4]);
        out.push_back(digits[b & 0x0F]);
    }
    return out;
}

}  // namespace gimbal::framing
