// The track's life (contract section 20), with time passed in.
#include <catch2/catch.hpp>

#include "track/ground/frame_clock.hpp"
#include "track/ground/track_state.hpp"

using namespace gimbal::track;
using Kind = TrackChange::Kind;

TEST_CASE("track state: lost when not seen, reacquired when seen again", "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 10}, 100);
    CHECK(m.phase() == TrackPhase::tracking);
    CHECK_FALSE(m.frame(100.1, true));
    const auto lost = m.frame(100.2, false);
    CHECK(lost.kind == Kind::lost);
    CHECK(m.phase() == TrackPhase::lost);
    CHECK(m.lost_since() == 100.2);
    CHECK_FALSE(m.frame(100.3, false));  // still lost: nothing new
    CHECK(m.frame(102.0, true).kind == Kind::reacquired);
    CHECK(m.phase() == TrackPhase::tracking);
    CHECK(m.frames() == 4);
    CHECK(m.lost_frames() == 2);
}

TEST_CASE("track state: lost for reacquire_s ends with timeout", "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 3}, 0);
    m.frame(0.5, false);
    CHECK_FALSE(m.frame(3.4, false));
    const auto ended = m.frame(3.5, false);
    CHECK(ended.kind == Kind::ended);
    CHECK(ended.reason == EndReason::timeout);
    CHECK(m.ended());
    CHECK(m.end_reason() == EndReason::timeout);
    CHECK_FALSE(m.frame(3.6, true));  // nothing after the end
    CHECK_FALSE(m.end(EndReason::stopped));
    CHECK(m.end_reason() == EndReason::timeout);
}

TEST_CASE("track state: no frames make it lost, then no_video", "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 5}, 0);
    m.frame(2, true);
    CHECK_FALSE(m.tick(2.9));
    const auto lost = m.tick(3.0);
    CHECK(lost.kind == Kind::lost);
    CHECK(m.lost_since() == 2);  // counted from the last frame seen
    CHECK_FALSE(m.tick(6.9));
    const auto ended = m.tick(7.0);
    CHECK(ended.kind == Kind::ended);
    CHECK(ended.reason == EndReason::no_video);
}

TEST_CASE("track state: lost by the picture, then frames stop: no_video", "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 5}, 0);
    m.frame(1, false);  // lost at 1
    m.frame(2, false);  // the last frame
    CHECK(m.tick(6.0).reason == EndReason::no_video);
}

TEST_CASE("track state: lost by the picture with frames coming: timeout via tick",
          "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 5}, 0);
    m.frame(1, false);
    m.frame(5.9, false);
    const auto ended = m.tick(6.0);
    CHECK(ended.kind == Kind::ended);
    CHECK(ended.reason == EndReason::timeout);
}

TEST_CASE("track state: stopped and overridden end it at once", "[track][state]") {
    TrackStateMachine a({}, 0);
    const auto stopped = a.end(EndReason::stopped);
    CHECK(stopped.kind == Kind::ended);
    CHECK(stopped.reason == EndReason::stopped);
    TrackStateMachine b({}, 0);
    b.frame(0.1, false);
    CHECK(b.end(EndReason::overridden).reason == EndReason::overridden);
    CHECK(b.phase() == TrackPhase::ended);
    CHECK(to_string(b.phase()) == "ended");
}

TEST_CASE("track state: reacquire_s 0 ends at the first loss", "[track][state]") {
    TrackStateMachine m({.lost_after_s = 1.0, .reacquire_s = 0}, 0);
    const auto c = m.frame(0.1, false);
    CHECK(c.kind == Kind::ended);
    CHECK(c.reason == EndReason::timeout);
}

TEST_CASE("frame clock: seconds from presentation times", "[track][state]") {
    FrameClock c;
    CHECK(c.time(900000) == 0);
    CHECK(c.time(906000) == Approx(1.0 / 15));
    CHECK(c.time(912000) == Approx(2.0 / 15));
    // The 33-bit wrap is a forward step.
    FrameClock w;
    w.time(FrameClock::wrap_90k - 3000);
    CHECK(w.time(3000) == Approx(6000.0 / 90000));
    CHECK(w.jumps() == 0);
    // A jump back or far ahead counts as the last good step; the clock never goes back.
    const double before = c.now();
    CHECK(c.time(100) == Approx(before + 1.0 / 15));
    CHECK(c.time(100 + 90000 * 60) == Approx(before + 2.0 / 15));
    CHECK(c.jumps() == 2);
    CHECK(c.time(100 + 90000 * 60 + 3000) == Approx(before + 2.0 / 15 + 3000.0 / 90000));
}
