#include "sim/read_faults.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::sim {

namespace {
// A byte on the line: start bit, 8 data bits, stop bit.
constexpr double bits_per_byte = 10.0;
// With a baud limit, at most this many bytes are read at once (a UART FIFO's worth).
constexpr std::size_t baud_chunk = 64;
}  // namespace

void ReadGate::session_start(double now_s) {
    session_start_s_ = now_s;
    line_free_s_ = now_s;
}

bool ReadGate::stalled(double now_s) const {
    if (options_.stall_for_s <= 0) return false;
    const double since = now_s - session_start_s_;
    return since >= options_.stall_after_s && since < options_.stall_after_s + options_.stall_for_s;
}

ReadGate::Budget ReadGate::budget(double now_s) const {
    if (stalled(now_s)) {
        const double resume = session_start_s_ + options_.stall_after_s + options_.stall_for_s;
        return {0, std::max(0.001, resume - now_s)};
    }
    if (options_.baud == 0) return {unlimited, 0};
    if (now_s < line_free_s_) return {0, std::max(0.001, line_free_s_ - now_s)};
    return {baud_chunk, 0};
}

void ReadGate::consumed(std::size_t n, double now_s) {
    if (options_.baud == 0 || n == 0) return;
    const double seconds = static_cast<double>(n) * bits_per_byte / options_.baud;
    line_free_s_ = std::max(line_free_s_, now_s) + seconds;
}

}  // namespace gimbal::sim
