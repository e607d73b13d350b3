// Frames what a controller sends a Viewpro gimbal: IN1/IN2/IN3 (header F9, id FB/FC, byte 3
// = FF marks IN3, checksum) and the 5-byte commands AA 55 {0F,06,36} XX FF. The mirror of
// OutputFramer, used by the simulator. A command whose fifth byte is not FF counts as a bad
// checksum: that end byte is its only integrity check.
#pragma once

#include "framing/scan_framer.hpp"
#include "protocols/viewpro/codec/framer_stats.hpp"
#include "protocols/viewpro/codec/input.hpp"

namespace gimbal::viewpro {

struct InputFrameRules {
    using Frame = InputFrame;
    using Stats = FramerStats;
    static constexpr auto frames = &FramerStats::frames;
    static constexpr std::size_t max_frame = max_input_frame_size;
    static bool is_start(std::uint8_t b) { return b == input_header || b == command_header0; }
    static framing::Probe probe(std::span<const std::uint8_t> data, InputFrame& out);
};

class InputFramer : public framing::ScanFramer<InputFrameRules> {};

}  // namespace gimbal::viewpro
