#include "track/ground/track_state.hpp"

namespace gimbal::track {

std::string_view to_string(TrackPhase phase) {
    switch (phase) {
        case TrackPhase::tracking:
            return "tracking";
        case TrackPhase::lost:
            return "lost";
        case TrackPhase::ended:
            return "ended";
    }
    return "ended";
}

TrackStateMachine::TrackStateMachine(TrackTiming timing, double now)
    : timing_(timing), last_frame_(now) {}

TrackChange TrackStateMachine::lose(double since) {
    phase_ = TrackPhase::lost;
    lost_since_ = since;
    return {TrackChange::Kind::lost};
}

TrackChange TrackStateMachine::timeout(double now) {
    if (phase_ != TrackPhase::lost || now - lost_since_ < timing_.reacquire_s) return {};
    const bool no_frames = now - last_frame_ >= timing_.lost_after_s;
    return end(no_frames ? EndReason::no_video : EndReason::timeout);
}

TrackChange TrackStateMachine::frame(double now, bool seen) {
    if (ended()) return {};
    last_frame_ = now;
    ++frames_;
    if (seen) {
        if (phase_ == TrackPhase::lost) {
            phase_ = TrackPhase::tracking;
            return {TrackChange::Kind::reacquired};
        }
        return {};
    }
    ++lost_frames_;
    if (phase_ == TrackPhase::tracking) {
        lose(now);
        // A zero reacquire_s ends at once; otherwise report the loss first.
        if (auto ended = timeout(now)) return ended;
        return {TrackChange::Kind::lost};
    }
    return timeout(now);
}

TrackChange TrackStateMachine::tick(double now) {
    if (ended()) return {};
    if (phase_ == TrackPhase::tracking && now - last_frame_ >= timing_.lost_after_s) {
        lose(last_frame_);
        if (auto ended = timeout(now)) return ended;
        return {TrackChange::Kind::lost};
    }
    return timeout(now);
}

TrackChange TrackStateMachine::end(EndReason reason) {
    if (ended()) return {};
    phase_ = TrackPhase::ended;
    reason_ = reason;
    return {TrackChange::Kind::ended, reason};
}

}  // namespace gimbal::track
