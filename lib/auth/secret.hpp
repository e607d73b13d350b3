// A key's secret as stored in its file (contract section 10): at least 32 random bytes as
// 64 or more hex characters; surrounding white space is ignored.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace gimbal::auth {

inline constexpr std::size_t min_secret_bytes = 32;

// The decoded bytes, or a message saying what is wrong with the text.
std::variant<std::vector<std::uint8_t>, std::string> parse_secret(std::string_view text);

// A new secret file's text: 32 random bytes as 64 hex characters and a newline.
std::string new_secret_text();

}  // namespace gimbal::auth
