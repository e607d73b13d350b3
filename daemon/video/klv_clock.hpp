// The PTS of the KLV that goes into MPEG-TS outputs: the latest video DTS (its PTS when it
// has no DTS), so metadata lines up with the picture it describes, and never going back -
// FFmpeg's demuxer rejects KLV whose timestamps go backwards - except across a jump of more
// than max_back_ticks (an encoder restarted with a new clock), which is followed. 33-bit
// 90 kHz timestamps, compared modulo 2^33. Pure.
#pragma once

#include <cstdint>
#include <optional>

#include "video/codec.hpp"

namespace gimbald::video {

class KlvClock {
  public:
    explicit KlvClock(std::uint64_t max_back_ticks = 10 * gimbal::video::pts_hz)
        : max_back_(max_back_ticks) {}

    void video(std::optional<std::uint64_t> dts_or_pts) {
        if (dts_or_pts) video_ = *dts_or_pts & (gimbal::video::pts_modulus - 1);
    }
    // The PTS for the next KLV unit; nullopt until video has been seen.
    std::optional<std::uint64_t> next() {
        if (!video_) return std::nullopt;
        std::uint64_t pts = *video_;
        if (last_) {
            const std::uint64_t behind = (*last_ - pts) & (gimbal::video::pts_modulus - 1);
            if (behind != 0 && behind <= max_back_) pts = *last_;
        }
        last_ = pts;
        return pts;
    }
    void reset() {
        video_.reset();
        last_.reset();
    }

  private:
    std::uint64_t max_back_;
    std::optional<std::uint64_t> video_;
    std::optional<std::uint64_t> last_;
};

}  // namespace gimbald::video
