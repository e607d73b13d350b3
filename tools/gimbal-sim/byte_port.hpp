// What gimbal-sim's TCP server and pty have in common: they hand received bytes to a callback
// and take bytes to send, dropping them when nobody is listening.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

namespace gimbal_sim {

using BytesHandler = std::function<void(std::span<const std::uint8_t>)>;

}  // namespace gimbal_sim
