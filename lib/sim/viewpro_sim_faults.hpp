// Byte-stream faults on a Viewpro gimbal's output, for tests of the receiving side: the
// Viewpro twin of FaultInjector (same options and counters). Corrupts the checksum of a
// fraction of the OUTx frames and inserts junk (a stray FE, sometimes a false FE id header,
// and noise) between frames. Bytes that are not a whole frame pass through untouched.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "sim/fault_injector.hpp"

namespace gimbal::sim {

class ViewproFaultInjector {
  public:
    explicit ViewproFaultInjector(const FaultOptions& options);

    // Appends `in`, with faults applied, to `out`.
    void apply(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out);
    const FaultStats& stats() const { return stats_; }
    bool active() const { return options_.corrupt_fraction > 0 || options_.junk_every > 0; }

  private:
    void append_junk(std::vector<std::uint8_t>& out);

    FaultOptions options_;
    std::mt19937 rng_;
    FaultStats stats_;
    unsigned frames_since_junk_ = 0;
};

}  // namespace gimbal::sim
