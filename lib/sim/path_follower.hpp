// Path mode (OrionPath): where on the path the gimbal looks, how far along it is, and the
// step-stare cycle (step, stare, wait for StareAck or time out, step again).
//
// Model: the look point sweeps from the first point to the last and stays at the last.
// Without step-stare it moves at a constant ground speed. With an along-track step angle the
// look point jumps by (slant range x step angle) along the path; at each station the gimbal
// slews, starts a stare once on target (or after a timeout), and moves on after a StareAck or
// when the stare time runs out. With cross-track steps each station is stared at from
// left to right at multiples of (step angle x cross ratio) across the path.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "sim/frames.hpp"

namespace gimbal::sim {

struct PathOptions {
    double scan_speed_mps = 100;       // continuous sweep speed of the look point
    double stare_time_s = 1.0;         // longest stare (StareStart maxStareTime, <= 2.55)
    double step_timeout_s = 2.0;       // stare anyway when not on target by then
    double on_target_rad = 0.5 * deg;  // pointing error that counts as on target
};

struct StepStare {
    double along_step = 0;     // rad; 0 = no step-stare
    unsigned cross_steps = 0;  // stares per station; more than 1 enables cross stepping
    double cross_ratio = 0;    // cross-track step / along-track step
};

// What a StareStart packet reports when a stare begins.
struct StareBegin {
    Vec3 point_ecef;               // desired stare point
    bool along_track = false;      // first stare at a station
    bool started_by_time = false;  // the step timed out before the gimbal was on target
    bool prev_terminated_by_time = false;
    double max_stare_time_s = 0;
    double prev_stare_time_s = 0;
    double stare_load = 0;
    double cross_angle = 0;  // rad, negative left of the path
    double slant_range_m = 0;
};

class PathFollower {
  public:
    PathFollower(std::vector<Vec3> points_ecef, StepStare step_stare, PathOptions options);

    // Runs dt seconds. pointing_error is the angle between the gimbal's line of sight and the
    // direction to look_point(). Returns what a stare that began in this step reports.
    std::optional<StareBegin> step(double dt, Vec3 gimbal_ecef, double pointing_error);
    // A matching StareAck: end the current stare now. False when not staring.
    bool acknowledge();

    Vec3 look_point() const;
    double progress() const;  // 0..1 along the path
    std::uint8_t from_index() const;
    std::uint8_t to_index() const;
    double stare_remaining_s() const { return phase_ == Phase::staring ? stare_left_ : 0.0; }
    bool staring() const { return phase_ == Phase::staring; }
    bool finished() const { return phase_ == Phase::finished; }
    bool step_stare() const { return step_.along_step > 0; }

  private:
    enum class Phase { sweeping, stepping, staring, finished };

    Vec3 point_at(double s) const;
    std::size_t segment_at(double s) const;
    unsigned stares_per_station() const;
    double cross_offset_angle() const;
    void end_stare(bool by_time);

    std::vector<Vec3> points_;
    std::vector<double> cumulative_;  // path length at each point
    StepStare step_;
    PathOptions options_;

    Phase phase_;
    double s_ = 0;              // distance of the look point (station) along the path
    unsigned cross_index_ = 0;  // which stare of the station
    double phase_time_ = 0;
    double stare_left_ = 0;
    double stare_elapsed_ = 0;
    double station_range_ = 0;  // slant range when the stare began
    bool prev_by_time_ = false;
    double prev_stare_time_ = 0;
    bool stared_before_ = false;
};

}  // namespace gimbal::sim
