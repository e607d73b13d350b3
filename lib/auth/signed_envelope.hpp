// The signed request datagram of contract section 10:
//   {"signed": {"key": ID, "payload": STRING, "mac": HEX}}
// `payload` is the request JSON as a string; `mac` is lower-case hex HMAC-SHA256 over the
// payload's UTF-8 bytes, keyed with the secret. Replies and pushes travel the same way.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "command/result.hpp"

namespace gimbal::auth {

struct SignedEnvelope {
    std::string key;
    std::string payload;
    std::string mac;  // hex as received
};

// A value of nullopt when `datagram` is not a signed envelope at all (no "signed" member);
// the envelope; or bad_request saying how it is malformed.
command::Result<std::optional<SignedEnvelope>> parse_signed(const nlohmann::json& datagram);

// True when `mac` is the HMAC of `payload` under `secret` (constant-time comparison).
bool mac_matches(const SignedEnvelope& envelope, std::span<const std::uint8_t> secret);

// The signed datagram text for `payload` (a JSON text).
std::string sign(std::string_view key_id, std::span<const std::uint8_t> secret,
                 const std::string& payload);

}  // namespace gimbal::auth
