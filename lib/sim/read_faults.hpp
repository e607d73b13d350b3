// Faults on the simulator's receiving side, for tests of the controller's send path: the
// gimbal stops reading for a while (its input buffers fill, the controller's writes block),
// or reads no faster than a serial line of a given baud rate (10 bits per byte) drains. Pure:
// the port asks how much it may read now and reports what it read; times are the caller's
// seconds.
#pragma once

#include <cstddef>
#include <limits>

namespace gimbal::sim {

struct ReadFaultOptions {
    double stall_after_s = 0;  // stop reading this long after a session starts ...
    double stall_for_s = 0;    // ... for this long; 0 = never
    unsigned baud = 0;         // read no faster than this line rate; 0 = as fast as it comes
};

class ReadGate {
  public:
    static constexpr std::size_t unlimited = std::numeric_limits<std::size_t>::max();

    explicit ReadGate(const ReadFaultOptions& options) : options_(options) {}

    bool active() const { return options_.stall_for_s > 0 || options_.baud > 0; }
    // A controller connected (TCP) or opened the device (pty): faults count from now.
    void session_start(double now_s);
    bool stalled(double now_s) const;

    // What the port may read at now_s: `bytes` (0 = nothing now; then ask again after
    // `retry_after_s`).
    struct Budget {
        std::size_t bytes;
        double retry_after_s;
    };
    Budget budget(double now_s) const;
    // `n` bytes were read at now_s.
    void consumed(std::size_t n, double now_s);

  private:
    ReadFaultOptions options_;
    double session_start_s_ = 0;
    double line_free_s_ = 0;  // when the simulated line has carried everything read so far
};

}  // namespace gimbal::sim
