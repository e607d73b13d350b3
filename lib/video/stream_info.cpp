#include "video/stream_info.hpp"

#include <algorithm>
#include <vector>

namespace gimbal::video {

namespace {
constexpr double window_s = 1.0;
constexpr std::size_t max_deltas = 31;
}  // namespace

void StreamInfoTracker::on_bytes(std::size_t n, double now_s) {
    info_.bytes += n;
    window_.emplace_back(now_s, n);
    window_bytes_ += n;
    while (!window_.empty() && window_.front().first <= now_s - window_s) {
        window_bytes_ -= window_.front().second;
        window_.pop_front();
    }
}

void StreamInfoTracker::on_access_unit(const AccessUnit& au) {
    if (info_.codec != au.codec) {
        reset();
        info_.codec = au.codec;
    }
    ++info_.access_units;
    if (au.key_frame) {
        ++info_.key_frames;
        if (const auto f = find_format(au.codec, au.data)) {
            info_.width = f->width;
            info_.height = f->height;
            vui_fps_ = f->fps;
        }
    }
    // Decode order steps: DTS when present (B-frames make PTS steps uneven).
    const std::optional<std::uint64_t> ts = au.dts ? au.dts : au.pts;
    if (ts) {
        if (last_ts_) {
            const std::uint64_t d = (*ts - *last_ts_) & (pts_modulus - 1);
            if (d > 0 && d < pts_hz) {  // skip jumps (restarts) and repeats
                deltas_.push_back(d);
                if (deltas_.size() > max_deltas) deltas_.pop_front();
            }
        }
        last_ts_ = ts;
    }
}

StreamInfo StreamInfoTracker::info(double now_s) const {
    StreamInfo out = info_;
    std::size_t bytes = 0;
    for (const auto& [t, n] : window_)
        if (t > now_s - window_s) bytes += n;
    out.bitrate_bps = static_cast<double>(bytes) * 8.0 / window_s;
    if (vui_fps_) {
        out.fps = vui_fps_;
    } else if (deltas_.size() >= 3) {
        std::vector<std::uint64_t> d(deltas_.begin(), deltas_.end());
        std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
        out.fps = static_cast<double>(pts_hz) / static_cast<double>(d[d.size() / 2]);
    }
    return out;
}

void StreamInfoTracker::reset() {
    const std::uint64_t bytes = info_.bytes;
    info_ = StreamInfo{};
    info_.bytes = bytes;
    vui_fps_.reset();
    last_ts_.reset();
    deltas_.clear();
}

}  // namespace gimbal::video
