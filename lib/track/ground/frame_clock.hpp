// Seconds from video presentation times (90 kHz), for a track's clock: the first frame is 0,
// each later one adds its step from the one before. A step that is not forward and short - a
// stream restarted, a PTS that jumped - counts as the last good step instead, so the clock
// never runs backwards or leaps; the 33-bit MPEG-TS wrap is a forward step like any other.
// Pure.
#pragma once

#include <cstdint>
#include <optional>

namespace gimbal::track {

class FrameClock {
  public:
    static constexpr std::int64_t wrap_90k = std::int64_t{1} << 33;
    static constexpr double max_step_s = 2.0;

    // The time of the frame shown at pts_90k.
    double time(std::int64_t pts_90k) {
        if (!last_) {
            last_ = pts_90k;
            return now_;
        }
        std::int64_t step = pts_90k - *last_;
        if (step < 0 && step + wrap_90k > 0 && step + wrap_90k <= max_step_90k) step += wrap_90k;
        double s = static_cast<double>(step) / 90000.0;
        if (step <= 0 || step > max_step_90k) {
            s = good_step_s_;
            ++jumps_;
        } else {
            good_step_s_ = s;
        }
        last_ = pts_90k;
        now_ += s;
        return now_;
    }
    double now() const { return now_; }
    std::uint64_t jumps() const { return jumps_; }

  private:
    static constexpr std::int64_t max_step_90k = static_cast<std::int64_t>(max_step_s * 90000);
    std::optional<std::int64_t> last_;
    double now_ = 0;
    double good_step_s_ = 1.0 / 15;
    std::uint64_t jumps_ = 0;
};

}  // namespace gimbal::track
