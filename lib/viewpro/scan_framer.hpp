// The streaming engine shared by the Viewpro framers, with no I/O: push() any chunk of bytes,
// get every complete, valid frame out in order. After a false start (a stray header byte, an
// unknown id, a bad checksum) it resumes the scan one byte after that start, so a valid frame
// hidden inside the bytes of a false one is still found.
//
// Rules supplies:
//   using Frame = ...;                        // what on_frame receives
//   static constexpr std::size_t max_frame;   // longest frame
//   static bool is_start(std::uint8_t);       // can a frame begin with this byte?
//   static Probe probe(std::span<const std::uint8_t> from_start, Frame& out);
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "framing/pending_bytes.hpp"

namespace gimbal::viewpro {

struct FramerStats {
    std::uint64_t bytes = 0;          // bytes pushed
    std::uint64_t frames = 0;         // valid frames delivered
    std::uint64_t bad_checksums = 0;  // candidate frames whose checksum (or end byte) failed
    std::uint64_t dropped_bytes = 0;  // bytes that belonged to no valid frame
};

namespace detail {

// What a Rules::probe() found at a start byte.
struct Probe {
    enum class Verdict : std::uint8_t { need_more, no_frame, bad_checksum, frame };
    Verdict verdict = Verdict::need_more;
    std::size_t size = 0;  // of the frame, when verdict == frame
};

template <class Rules>
class ScanFramer {
  public:
    using Frame = typename Rules::Frame;

    // Calls on_frame(const Frame&) for each valid frame in `bytes`, in order.
    template <class F>
    void push(std::span<const std::uint8_t> bytes, F&& on_frame) {
        stats_.bytes += bytes.size();
        pending_.feed(bytes, Rules::max_frame,
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
        std::size_t i = 0;
        while (i < n) {
            if (!Rules::is_start(data[i])) {
                ++stats_.dropped_bytes;
                ++i;
                continue;
            }
            const Probe p = Rules::probe(data.subspan(i), frame_);
            switch (p.verdict) {
                case Probe::Verdict::need_more:
                    return i;
                case Probe::Verdict::bad_checksum:
                    ++stats_.bad_checksums;
                    [[fallthrough]];
                case Probe::Verdict::no_frame:
                    ++stats_.dropped_bytes;
                    ++i;  // re-scan from the byte after this false start
                    continue;
                case Probe::Verdict::frame:
                    ++stats_.frames;
                    i += p.size;
                    on_frame(static_cast<const Frame&>(frame_));
                    continue;
            }
        }
        return i;
    }

    framing::PendingBytes pending_;
    Frame frame_{};
    FramerStats stats_;
};

}  // namespace detail
}  // namespace gimbal::viewpro
