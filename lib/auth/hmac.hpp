// HMAC-SHA256 and the hex text it travels as (contract section 10). The primitive comes
// from OpenSSL's libcrypto; nothing here hand-rolls SHA-256 or HMAC.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gimbal::auth {

using Mac = std::array<std::uint8_t, 32>;

Mac hmac_sha256(std::span<const std::uint8_t> key, std::string_view message);

// Lower-case hex.
std::string to_hex(std::span<const std::uint8_t> bytes);
// Hex text (either case) -> bytes; nullopt on an odd length or a non-hex character.
std::optional<std::vector<std::uint8_t>> from_hex(std::string_view hex);

// Compares two MACs in time independent of where they differ.
bool equal_constant_time(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b);

// `count` random bytes from the operating system's generator (OpenSSL RAND_bytes).
std::vector<std::uint8_t> random_bytes(std::size_t count);

}  // namespace gimbal::auth
