// The MAVLink framer, with each message's wire bytes: what the recorder's splitter, the
// export's track decoder and gimbal-sim's --rx-log need besides the decoded message. Every
// byte before a delivered frame is accounted for in the framer's counters (frames, dropped,
// skipped), so a frame's place in the stream is their sum less its own size. Pure.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mavlink/framer.hpp"

namespace gimbal::protocols {

struct ScannedFrame {
    const mavlink::Message& message;
    std::span<const std::uint8_t> bytes;
};

class MavlinkFrameScanner {
  public:
    template <class F>
    void push(std::span<const std::uint8_t> bytes, F&& on_frame) {
        held_.insert(held_.end(), bytes.begin(), bytes.end());
        framer_.push(bytes, [&](const mavlink::Message& m) {
            const auto& s = framer_.stats();
            const std::uint64_t end = s.frame_bytes + s.dropped_bytes + s.skipped_bytes;
            const std::uint64_t size = s.frame_bytes - frame_bytes_seen_;
            frame_bytes_seen_ = s.frame_bytes;
            const auto at = static_cast<std::size_t>(end - size - held_from_);
            on_frame(ScannedFrame{m, std::span(held_).subspan(at, static_cast<std::size_t>(size))});
        });
        // Keep only what the framer still holds (an unfinished frame).
        const auto& s = framer_.stats();
        const std::uint64_t done = s.frame_bytes + s.dropped_bytes + s.skipped_bytes;
        const auto drop = static_cast<std::size_t>(done - held_from_);
        held_.erase(held_.begin(), held_.begin() + static_cast<long>(drop));
        held_from_ = done;
    }
    void reset() {
        framer_.reset();
        const auto& s = framer_.stats();
        held_.clear();
        held_from_ = s.frame_bytes + s.dropped_bytes + s.skipped_bytes;
    }
    const mavlink::FramerStats& stats() const { return framer_.stats(); }
    std::size_t pending_bytes() const { return framer_.pending_bytes(); }

  private:
    // Signed frames too (a signed device link), unverified: these read what is on the wire.
    mavlink::Framer framer_{{.accept_signed = true, .signing_key = std::nullopt}};
    std::vector<std::uint8_t> held_;  // stream bytes from stream offset held_from_ on
    std::uint64_t held_from_ = 0;
    std::uint64_t frame_bytes_seen_ = 0;
};

}  // namespace gimbal::protocols
