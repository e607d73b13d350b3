// Checks signed requests against the configured keys (contract section 10): key known, MAC
// right, payload a JSON object with `ts` within max_skew_s of the clock and a fresh `nonce`.
// The role check happens once the command is known (roles.hpp). Time is passed in.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "auth/nonce_window.hpp"
#include "auth/roles.hpp"
#include "auth/signed_envelope.hpp"

namespace gimbal::auth {

struct Key {
    std::string id;
    std::vector<std::uint8_t> secret;
    Roles roles;
};

struct Verified {
    const Key* key = nullptr;
    nlohmann::json request;  // the payload, parsed
    std::string nonce;
};

// A signed envelope's payload as a JSON object: the request limits on its bytes, then its one
// parse (command::parse_object). bad_json / too_large say "the signed payload ...".
Result<nlohmann::json> read_signed_payload(std::string_view payload);

class Verifier {
  public:
    Verifier(std::vector<Key> keys, double max_skew_s, std::size_t nonces_per_key = 65536);

    // A refusal is an Error whose message is the reply's: it names what was wrong. Its code
    // is forbidden, or bad_json / too_large for a payload that is not a JSON object within
    // the request limits.
    // authenticate(), read_signed_payload(), then accept().
    Result<Verified> verify(const SignedEnvelope& envelope, std::int64_t now_unix_ms);
    // The key the envelope names, when it exists and the MAC over the payload is right.
    // Nothing of the payload is read and nothing is remembered: a caller may use the key
    // (e.g. as a rate-limit key) before accept() spends a nonce.
    Result<const Key*> authenticate(const SignedEnvelope& envelope) const;
    // The payload (read_signed_payload) of an envelope `key` authenticated: `ts` within
    // max_skew_s of now, a fresh `nonce` (remembered from here on). The payload becomes the
    // Verified request: it is not parsed again.
    Result<Verified> accept(const Key& key, nlohmann::json payload, std::int64_t now_unix_ms);
    const Key* find(const std::string& id) const;
    bool empty() const { return keys_.empty(); }

  private:
    std::vector<Key> keys_;
    std::int64_t max_skew_ms_;
    std::map<std::string, NonceWindow> nonces_;
};

inline constexpr std::size_t min_nonce_chars = 8;
inline constexpr std::size_t max_nonce_chars = 64;

}  // namespace gimbal::auth
