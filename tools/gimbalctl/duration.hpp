// Seconds as typed on the command line (--timeout 0.3) -> a steady-clock duration for timers.
#pragma once

#include <chrono>

namespace gimbalctl {

inline std::chrono::steady_clock::duration seconds(double value) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(value));
}

}  // namespace gimbalctl
