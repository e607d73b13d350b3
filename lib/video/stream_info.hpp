// What an input reports about its video (contract section 17 STATE `video`): codec, size
// and frame rate from the SPS (frame rate from the timestamps when the SPS has no VUI
// timing), and the bit rate over the last second. Pure: arrival times are passed in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "video/codec.hpp"
#include "video/nal.hpp"

namespace gimbal::video {

struct StreamInfo {
    std::optional<Codec> codec;
    int width = 0;
    int height = 0;
    std::optional<double> fps;
    double bitrate_bps = 0;
    std::uint64_t access_units = 0;
    std::uint64_t key_frames = 0;
    std::uint64_t bytes = 0;  // received (TS or RTP payload bytes)
};

class StreamInfoTracker {
  public:
    // Bytes as they arrive (a datagram, an RTP payload).
    void on_bytes(std::size_t n, double now_s);
    void on_access_unit(const AccessUnit& au);
    StreamInfo info(double now_s) const;
    void reset();

  private:
    StreamInfo info_;
    std::optional<double> vui_fps_;
    std::deque<std::pair<double, std::size_t>> window_;  // arrivals in the last second
    std::size_t window_bytes_ = 0;
    std::optional<std::uint64_t> last_ts_;
    std::deque<std::uint64_t> deltas_;  // recent DTS (or PTS) steps, 90 kHz
};

}  // namespace gimbal::video
