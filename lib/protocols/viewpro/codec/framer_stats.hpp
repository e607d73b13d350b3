// The counters of both Viewpro framers (OUTx from the gimbal, IN/commands to it).
#pragma once

#include <cstdint>

namespace gimbal::viewpro {

struct FramerStats {
    std::uint64_t bytes = 0;          // bytes pushed
    std::uint64_t frames = 0;         // valid frames delivered
    std::uint64_t bad_checksums = 0;  // candidate frames whose checksum (or end byte) failed
    std::uint64_t dropped_bytes = 0;  // bytes that belonged to no valid frame
};

}  // namespace gimbal::viewpro
