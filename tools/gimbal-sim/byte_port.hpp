// What gimbal-sim's TCP server and pty have in common: they hand received bytes to a callback
// and take bytes to send, dropping them when nobody is listening. A read policy (fault
// injection) may make them read slower, or not at all for a while.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

namespace gimbal_sim {

using BytesHandler = std::function<void(std::span<const std::uint8_t>)>;

// How much a port may read now: 0 bytes means "ask again after retry_after_s".
struct ReadBudget {
    std::size_t bytes;
    double retry_after_s;
};
using ReadPolicy = std::function<ReadBudget()>;

}  // namespace gimbal_sim
