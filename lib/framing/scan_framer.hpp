// The streaming engine every byte-scanning framer shares (lib/<protocol>/*framer*), with
// no I/O: push() any chunk of bytes, get every complete, valid frame out in order. After a
// false start (a stray start byte, an unknown id, an impossible length, a bad checksum) it
// resumes the scan one byte after that start, so a valid frame hidden inside the bytes of a
// false one is still found - what the reference SDKs' byte parsers lose.
//
// Rules supplies:
//   using Frame = ...;                        // what on_frame receives
//   using Stats = ...;                        // counters: bytes, bad_checksums, dropped_bytes,
//                                             // the member `frames` points to, and optionally
//                                             // oversize (false starts with a length too big)
//   static constexpr auto frames = &Stats::X; // the counter of delivered frames
//   static constexpr std::size_t max_frame;   // longest frame
//   static bool is_start(std::uint8_t);       // can a frame begin with this byte?
//   static Probe probe(std::span<const std::uint8_t> from_start, Frame& out);
// and optionally, to skip junk faster than byte by byte:
//   static std::size_t next_start(std::span<const std::uint8_t> data, std::size_t from);
//     // the index of the next byte at or after `from` that can begin a frame, or data.size()
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "framing/pending_bytes.hpp"

namespace gimbal::framing {

// What Rules::probe() found at a start byte.
struct Probe {
    enum class Verdict : std::uint8_t {
        need_more,     // the frame may still complete: wait for more bytes
        no_frame,      // not a frame after all (wrong second sync byte, unknown id)
        oversize,      // its length field is longer than any frame
        bad_checksum,  // complete, but its checksum (or end byte) failed
        frame,         // a valid frame of `size` bytes, written to `out`
    };
    Verdict verdict = Verdict::need_more;
    std::size_t size = 0;  // of the frame, when verdict == frame
};

template <class Rules>
class ScanFramer {
  public:
    using Frame = typename Rules::Frame;
    using Stats = typename Rules::Stats;

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

    const Stats& stats() const { return stats_; }
    std::size_t pending_bytes() const { return pending_.size(); }

  private:
    static std::size_t next_start(std::span<const std::uint8_t> data, std::size_t from) {
        if constexpr (requires { Rules::next_start(data, from); }) {
            return Rules::next_start(data, from);
        } else {
            while (from < data.size() && !Rules::is_start(data[from])) ++from;
            return from;
        }
    }

    // Returns how many leading bytes of `data` are finished with; the rest is an unfinished
    // frame that needs more bytes.
    template <class F>
    std::size_t scan(std::span<const std::uint8_t> data, F& on_frame) {
        using Verdict = Probe::Verdict;
        const std::size_t n = data.size();
        std::size_t i = 0;
        while (i < n) {
            const std::size_t start = next_start(data, i);
            stats_.dropped_bytes += start - i;
            i = start;
            if (i == n) break;
            const Probe p = Rules::probe(data.subspan(i), frame_);
            switch (p.verdict) {
                case Verdict::need_more:
                    return i;
                case Verdict::oversize:
                    if constexpr (requires { stats_.oversize; }) ++stats_.oversize;
                    break;
                case Verdict::bad_checksum:
                    ++stats_.bad_checksums;
                    break;
                case Verdict::no_frame:
                    break;
                case Verdict::frame:
                    ++(stats_.*Rules::frames);
                    i += p.size;
                    on_frame(static_cast<const Frame&>(frame_));
                    continue;
            }
            ++stats_.dropped_bytes;
            ++i;  // re-scan from the byte after this false start
        }
        return i;
    }

    PendingBytes pending_;
    Frame frame_{};
    Stats stats_{};
};

}  // namespace gimbal::framing
