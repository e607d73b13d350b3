// --key-file/--key-id: requests leave as signed datagrams (contract section 10) and replies
// and subscription datagrams are accepted only with a valid MAC from the same key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "json_types.hpp"

namespace gimbalctl {

struct SigningKey {
    std::string id;
    std::vector<std::uint8_t> secret;
};

// Reads the key's secret file; nullopt with `problem` set when it cannot be used.
std::optional<SigningKey> load_signing_key(const std::string& file, const std::string& id,
                                           std::string& problem);

struct GlobalOptions;
// The key of --key-file/--key-id, or nullopt when not signing. When the file cannot be used
// the problem is printed and `status` set to the usage exit status.
std::optional<SigningKey> signing_key_for(const GlobalOptions& globals, int& status);

class Sealer {
  public:
    explicit Sealer(std::optional<SigningKey> key) : key_(std::move(key)) {}

    bool signing() const { return key_.has_value(); }
    // The datagram for `request`: plain JSON, or signed with a fresh `ts` and `nonce`.
    std::string seal(const Json& request);
    // The nonce of the last sealed request (a signed reply must carry it).
    const std::string& last_nonce() const { return nonce_; }

    enum class Opened {
        plain,      // not a signed datagram: left as it is
        authentic,  // signed by our key: replaced by its payload
        forged,     // signed, but not by our key or with a wrong MAC
    };
    Opened open(Json& datagram) const;

    // `timestamp_ms` and nonces are taken from the system; tests of the daemon pin neither.
  private:
    std::optional<SigningKey> key_;
    std::string nonce_;
};

// `gimbalctl keygen FILE`: a new secret file, mode 0600; refuses to overwrite. Returns the
// exit status.
int run_keygen(const std::string& file);

}  // namespace gimbalctl
