// A track's life, shared by gimbald and gimbal-track (contract section 20): tracking, lost
// (the object not seen: low confidence, out of the picture, or no frame for lost_after_s),
// ended (stopped, overridden, timeout: lost for reacquire_s; no_video: lost for reacquire_s
// with no frame for lost_after_s). A track seen again while lost is reacquired under the
// same id. Time is passed in (seconds, any origin); nothing happens by itself. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "track/wire/messages.hpp"

namespace gimbal::track {

using wire::EndReason;

struct TrackTiming {
    double lost_after_s = 1.0;  // no frame for this long: lost
    double reacquire_s = 10;    // lost for this long: ended
};

enum class TrackPhase : std::uint8_t { tracking, lost, ended };
std::string_view to_string(TrackPhase phase);

// What a call changed: nothing, or the event to report (track_lost, track_reacquired,
// track_end with its reason).
struct TrackChange {
    enum class Kind : std::uint8_t { none, lost, reacquired, ended };
    Kind kind = Kind::none;
    EndReason reason = EndReason::stopped;  // for ended
    explicit operator bool() const { return kind != Kind::none; }
};

class TrackStateMachine {
  public:
    // Starts tracking at `now`.
    TrackStateMachine(TrackTiming timing, double now);

    // A frame's outcome at time `now`: the object seen (confident) or not.
    TrackChange frame(double now, bool seen);
    // Time passes without a frame.
    TrackChange tick(double now);
    // Ended from outside (stopped, overridden); nothing once ended.
    TrackChange end(EndReason reason);

    TrackPhase phase() const { return phase_; }
    bool ended() const { return phase_ == TrackPhase::ended; }
    std::optional<EndReason> end_reason() const { return reason_; }
    // Since when the object has not been seen (when lost).
    double lost_since() const { return lost_since_; }
    double last_frame() const { return last_frame_; }
    std::uint64_t frames() const { return frames_; }
    std::uint64_t lost_frames() const { return lost_frames_; }
    const TrackTiming& timing() const { return timing_; }

  private:
    TrackChange lose(double since);
    TrackChange timeout(double now);

    TrackTiming timing_;
    TrackPhase phase_ = TrackPhase::tracking;
    std::optional<EndReason> reason_;
    double last_frame_;
    double lost_since_ = 0;
    std::uint64_t frames_ = 0;
    std::uint64_t lost_frames_ = 0;
};

}  // namespace gimbal::track
