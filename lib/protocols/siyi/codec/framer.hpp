// Streaming framer for SIYI's SDK protocol with no I/O: push() any chunk of bytes, get every
// complete, CRC-valid frame out in order. The shared scan engine (framing/scan_framer.hpp)
// with SIYI's rules: STX 55 66, length, CRC16. After a false sync (a stray 55, a cut-off
// header, a corrupted length, a bad CRC) it resumes one byte after that 55, so a frame hidden
// behind it is never lost - where a byte-at-a-time parser such as ArduPilot's AP_Mount_Siyi
// restarts after the whole false frame.
#pragma once

#include <cstdint>
#include <span>

#include "framing/scan_framer.hpp"
#include "protocols/siyi/codec/frame.hpp"

namespace gimbal::siyi {

struct FramerStats {
    std::uint64_t bytes = 0;          // bytes pushed
    std::uint64_t frames = 0;         // valid frames delivered
    std::uint64_t bad_checksums = 0;  // candidate frames whose CRC failed
    std::uint64_t dropped_bytes = 0;  // bytes that belonged to no valid frame
    std::uint64_t oversize = 0;       // candidates with a Data_len over max_data_length
};

struct FrameRules {
    using Frame = siyi::Frame;
    using Stats = FramerStats;
    static constexpr auto frames = &FramerStats::frames;
    static constexpr std::size_t max_frame = max_frame_size;

    static bool is_start(std::uint8_t b) { return b == stx0; }
    static std::size_t next_start(std::span<const std::uint8_t> data, std::size_t from);
    static framing::Probe probe(std::span<const std::uint8_t> from_start, Frame& out);
};

class Framer : public framing::ScanFramer<FrameRules> {};

}  // namespace gimbal::siyi
