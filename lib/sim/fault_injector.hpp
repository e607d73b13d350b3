// Byte-stream faults for tests of the receiving side: corrupt the checksum of a fraction of
// the frames, and insert junk (a stray sync byte and noise) between frames. Works on the
// output of Device::advance(), which is always whole frames; bytes that do not parse as a
// frame pass through untouched. Seeded, so a test run can be repeated.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace gimbal::sim {

struct FaultOptions {
    double corrupt_fraction = 0;  // 0..1: share of frames sent with a wrong checksum
    unsigned junk_every = 0;      // insert junk after every N frames; 0 = never
    std::uint32_t seed = 1;
};

struct FaultStats {
    std::uint64_t frames = 0;
    std::uint64_t corrupted = 0;
    std::uint64_t junk_inserts = 0;
};

class FaultInjector {
  public:
    explicit FaultInjector(const FaultOptions& options);

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
