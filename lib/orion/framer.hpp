// Streaming OrionPublic framer with no I/O: push() any chunk of bytes, get every complete,
// checksum-valid packet out in order. After a false sync (a stray D0, a cut-off header, a
// corrupted length, a bad checksum) it resumes the scan one byte after that sync, so a valid
// packet hidden inside the bytes of a false one is still found.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "framing/pending_bytes.hpp"
#include "orion/framing.hpp"

namespace gimbal::orion {

struct FramerStats {
    std::uint64_t bytes = 0;          // bytes pushed
    std::uint64_t packets = 0;        // valid packets delivered
    std::uint64_t bad_checksums = 0;  // candidate frames whose checksum failed
    std::uint64_t dropped_bytes = 0;  // bytes that belonged to no valid packet
    std::uint64_t oversize = 0;       // candidate frames with a length over 140
};

class Framer {
  public:
    // Calls on_frame(const Frame&) for each valid packet in `bytes`, in order.
    template <class F>
    void push(std::span<const std::uint8_t> bytes, F&& on_frame) {
        stats_.bytes += bytes.size();
        pending_.feed(bytes, max_frame_size,
                      [&](std::span<const std::uint8_t> data) { return scan(data, on_frame); });
    }

    std::vector<Frame> push(std::span<const std::uint8_t> bytes) {
        std::vector<Frame> frames;
        push(bytes, [&](const Frame& f) { frames.push_back(f); });
        return frames;
    }

    // Forget a partial frame (after a reconnect the old bytes belong to nothing).
    void reset() { stats_.dropped_bytes += pending_.clear(); }

    const FramerStats& stats() const { return stats_; }
    std::size_t pending_bytes() const { return pending_.size(); }

  private:
    // Returns how many leading bytes of `data` are finished with; the rest is an unfinished
    // frame that needs more bytes.
    template <class F>
    std::size_t scan(std::span<const std::uint8_t> data, F& on_frame) {
        const std::size_t n = data.size();
        const std::uint8_t* base = data.data();
        std::size_t i = 0;
        while (i < n) {
            if (base[i] != sync0) {  // in a clean stream the next frame starts right here
                const void* hit = std::memchr(base + i, sync0, n - i);
                if (!hit) {
                    stats_.dropped_bytes += n - i;
                    return n;
                }
                const auto at =
                    static_cast<std::size_t>(static_cast<const std::uint8_t*>(hit) - base);
                stats_.dropped_bytes += at - i;
                i = at;
            }
            if (n - i < 2) return i;
            if (base[i + 1] != sync1) {
                ++stats_.dropped_bytes;
                ++i;
                continue;
            }
            if (n - i < header_size) return i;
            const std::size_t len = base[i + 3];
            if (len > max_data_length) {
                ++stats_.oversize;
                ++stats_.dropped_bytes;
                ++i;
                continue;
            }
            const std::size_t total = header_size + len + checksum_size;
            if (n - i < total) return i;
            const std::uint16_t sum = fletcher251({base + i, header_size + len});
            const std::size_t c = i + header_size + len;
            if (base[c] != (sum >> 8) || base[c + 1] != (sum & 0xFF)) {
                ++stats_.bad_checksums;
                ++stats_.dropped_bytes;
                ++i;  // re-scan from the byte after this false sync
                continue;
            }
            frame_.id = base[i + 2];
            frame_.payload.size = len;
            std::memcpy(frame_.payload.bytes.data(), base + i + header_size, len);
            ++stats_.packets;
            i += total;
            on_frame(static_cast<const Frame&>(frame_));
        }
        return i;
    }

    framing::PendingBytes pending_;
    Frame frame_;
    FramerStats stats_;
};

}  // namespace gimbal::orion
