// Helpers shared by the lib/klv unit tests.
#pragma once

#include <cctype>
#include <string>

#include "klv/local_set.hpp"

namespace klv_test {

inline gimbal::klv::Bytes from_hex(const std::string& text) {
    gimbal::klv::Bytes out;
    std::string digits;
    for (const char c : text)
        if (std::isxdigit(static_cast<unsigned char>(c))) digits.push_back(c);
    for (std::size_t i = 0; i + 1 < digits.size(); i += 2)
        out.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
    return out;
}

inline std::string to_hex(const gimbal::klv::Bytes& bytes) {
    static constexpr char digits[] = "0123456789ABCDEF";
    std::string s;
    for (const auto b : bytes) {
        s.push_back(digits[b >> 4]);
        s.push_back(digits[b & 15]);
    }
    return s;
}

// The value bytes encode() writes for one item ("" and the error when it refuses).
inline std::string encoded_hex(std::uint32_t tag, const gimbal::klv::Value& value,
                               std::uint8_t length = 0, std::string* error = nullptr) {
    gimbal::klv::Bytes out;
    const auto encoded = gimbal::klv::encode_value({tag, value, length}, out);
    if (!encoded) {
        if (error != nullptr) *error = encoded.error().message;
        return "";
    }
    return to_hex(out);
}

inline nlohmann::json decoded(std::uint32_t tag, const std::string& hex,
                              gimbal::klv::Digits digits = gimbal::klv::Digits::exact) {
    bool valid = true;
    const auto bytes = from_hex(hex);
    auto json = gimbal::klv::value_json(*gimbal::klv::find_tag(tag), bytes, digits, valid);
    if (!valid) return "invalid";
    return json;
}

}  // namespace klv_test
