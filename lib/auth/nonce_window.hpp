// Replay protection for one key: every nonce seen within the time window is remembered until
// its request's `ts` falls out of the window (after that the timestamp check rejects it
// anyway). Bounded: when full, new requests are refused rather than forgetting nonces that
// could still be replayed. Time is passed in (milliseconds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>

namespace gimbal::auth {

class NonceWindow {
  public:
    explicit NonceWindow(std::size_t capacity = 65536) : capacity_(capacity) {}

    enum class Result { fresh, replayed, full };
    // Records `nonce`, to be forgotten at `forget_at_ms`; `now_ms` first drops what expired.
    Result remember(const std::string& nonce, std::int64_t forget_at_ms, std::int64_t now_ms);
    std::size_t size() const { return by_nonce_.size(); }

  private:
    std::size_t capacity_;
    std::map<std::string, std::int64_t> by_nonce_;
    std::set<std::pair<std::int64_t, std::string>> by_expiry_;
};

}  // namespace gimbal::auth
