// Streaming OrionPublic framer with no I/O: push() any chunk of bytes, get every complete,
// checksum-valid packet out in order. The shared scan engine (framing/scan_framer.hpp) with
// Orion's rules: sync D0 0D, id, length, data, Fletcher-251. After a false sync (a stray D0,
// a cut-off header, a corrupted length, a bad checksum) it resumes one byte after that sync,
// so a valid packet hidden inside the bytes of a false one is still found.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>

#include "framing/scan_framer.hpp"
#include "protocols/orion/codec/framing.hpp"

namespace gimbal::orion {

struct FramerStats {
    std::uint64_t bytes = 0;          // bytes pushed
    std::uint64_t packets = 0;        // valid packets delivered
    std::uint64_t bad_checksums = 0;  // candidate frames whose checksum failed
    std::uint64_t dropped_bytes = 0;  // bytes that belonged to no valid packet
    std::uint64_t oversize = 0;       // candidate frames with a length over 140
};

struct FrameRules {
    using Frame = orion::Frame;
    using Stats = FramerStats;
    static constexpr auto frames = &FramerStats::packets;
    static constexpr std::size_t max_frame = max_frame_size;

    static bool is_start(std::uint8_t b) { return b == sync0; }

    // In a clean stream the next frame starts right at `from`; otherwise memchr finds it.
    static std::size_t next_start(std::span<const std::uint8_t> data, std::size_t from) {
        if (from >= data.size() || data[from] == sync0) return from;
        const void* hit = std::memchr(data.data() + from, sync0, data.size() - from);
        return hit ? static_cast<std::size_t>(static_cast<const std::uint8_t*>(hit) - data.data())
                   : data.size();
    }

    static framing::Probe probe(std::span<const std::uint8_t> d, Frame& out) {
        using Verdict = framing::Probe::Verdict;
        if (d.size() < 2) return {Verdict::need_more};
        if (d[1] != sync1) return {Verdict::no_frame};
        if (d.size() < header_size) return {Verdict::need_more};
        const std::size_t len = d[3];
        if (len > max_data_length) return {Verdict::oversize};
        const std::size_t total = header_size + len + checksum_size;
        if (d.size() < total) return {Verdict::need_more};
        const std::uint16_t sum = fletcher251(d.first(header_size + len));
        const std::size_t c = header_size + len;
        if (d[c] != (sum >> 8) || d[c + 1] != (sum & 0xFF)) return {Verdict::bad_checksum};
        out.id = d[2];
        out.payload.size = len;
        std::memcpy(out.payload.bytes.data(), d.data() + header_size, len);
        return {Verdict::frame, total};
    }
};

class Framer : public framing::ScanFramer<FrameRules> {};

}  // namespace gimbal::orion
