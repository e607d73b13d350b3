// Byte-stream faults for tests of the receiving side: corrupt the checksum of a fraction of
// the frames, and insert junk (a stray sync byte, sometimes a false header, and noise)
// between frames. Works on the output of Device::advance(), which is always whole frames;
// bytes that do not parse as a frame pass through untouched. Seeded, so a test run can be
// repeated. One injector serves every protocol: a FrameShape says what a frame looks like.
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

// How to find whole frames in a protocol's output (its simulator hook's fault_frames,
// protocols/simulator.hpp). The checksum is always the last byte.
struct FrameShape {
    // Length of the whole frame starting at in[0], or 0 when no frame starts there.
    std::size_t (*frame_size_at)(std::span<const std::uint8_t> in);
    std::uint8_t sync0;  // junk starts with a stray sync0 ...
    std::uint8_t sync1;  // ... sometimes followed by sync1: a false header
};

class FaultInjector {
  public:
    explicit FaultInjector(const FaultOptions& options, FrameShape shape);

    // Appends `in`, with faults applied, to `out`.
    void apply(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out);
    const FaultStats& stats() const { return stats_; }
    bool active() const { return options_.corrupt_fraction > 0 || options_.junk_every > 0; }

  private:
    void append_junk(std::vector<std::uint8_t>& out);

    FaultOptions options_;
    FrameShape shape_;
    std::mt19937 rng_;
    FaultStats stats_;
    unsigned frames_since_junk_ = 0;
};

}  // namespace gimbal::sim
