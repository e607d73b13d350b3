// Frames the gimbal's output stream: header FE, id FB/FC/FD, the length that id implies,
// checksum. Tells OUT3 from OUT4 by byte 3. This is what the daemon runs on a Viewpro link.
#pragma once

#include "framing/scan_framer.hpp"
#include "protocols/viewpro/codec/framer_stats.hpp"
#include "protocols/viewpro/codec/output.hpp"

namespace gimbal::viewpro {

struct OutputFrameRules {
    using Frame = OutputFrame;
    using Stats = FramerStats;
    static constexpr auto frames = &FramerStats::frames;
    static constexpr std::size_t max_frame = max_output_frame_size;
    static bool is_start(std::uint8_t b) { return b == output_header; }
    static framing::Probe probe(std::span<const std::uint8_t> data, OutputFrame& out);
};

class OutputFramer : public framing::ScanFramer<OutputFrameRules> {};

}  // namespace gimbal::viewpro
