#include "sim/path_follower.hpp"

#include <algorithm>

namespace gimbal::sim {

PathFollower::PathFollower(std::vector<Vec3> points_ecef, StepStare step_stare, PathOptions options)
    : points_(std::move(points_ecef)), step_(step_stare), options_(options) {
    if (points_.empty()) points_.push_back(Vec3{});  // callers pass at least one point
    cumulative_.push_back(0);
    for (std::size_t i = 1; i < points_.size(); ++i)
        cumulative_.push_back(cumulative_.back() + norm(points_[i] - points_[i - 1]));
    phase_ = step_stare.along_step > 0 ? Phase::stepping : Phase::sweeping;
    options_.stare_time_s = std::clamp(options_.stare_time_s, 0.0, 2.55);
}

std::size_t PathFollower::segment_at(double s) const {
    if (points_.size() < 2) return 0;
    std::size_t i = 0;
    while (i + 2 < points_.size() && s >= cumulative_[i + 1]) ++i;
    return i;
}

Vec3 PathFollower::point_at(double s) const {
    if (points_.size() < 2) return points_.front();
    const std::size_t i = segment_at(s);
    const double length = cumulative_[i + 1] - cumulative_[i];
    const double f = length > 0 ? std::clamp((s - cumulative_[i]) / length, 0.0, 1.0) : 1.0;
    return points_[i] + f * (points_[i + 1] - points_[i]);
}

unsigned PathFollower::stares_per_station() const {
    return step_.cross_steps > 1 && step_.cross_ratio > 0 ? step_.cross_steps : 1;
}

// Angle of the current stare across the path: stares run left to right, centred on the path.
double PathFollower::cross_offset_angle() const {
    const unsigned n = stares_per_station();
    if (n <= 1) return 0;
    const double centred = static_cast<double>(cross_index_) - static_cast<double>(n - 1) / 2;
    return centred * step_.along_step * step_.cross_ratio;
}

Vec3 PathFollower::look_point() const {
    const Vec3 on_path = point_at(s_);
    const double angle = cross_offset_angle();
    if (angle == 0 || points_.size() < 2) return on_path;
    const std::size_t i = segment_at(s_);
    const Lla here = to_lla(on_path);
    const Vec3 down = ned_to_ecef(here.lat, here.lon) * Vec3{0, 0, 1};
    const Vec3 right = normalized(cross(down, points_[i + 1] - points_[i]));
    return on_path + (angle * station_range_) * right;
}

double PathFollower::progress() const {
    const double total = cumulative_.back();
    if (total <= 0) return phase_ == Phase::finished ? 1.0 : 0.0;
    return std::clamp(s_ / total, 0.0, 1.0);
}

std::uint8_t PathFollower::from_index() const {
    return static_cast<std::uint8_t>(segment_at(s_));
}

std::uint8_t PathFollower::to_index() const {
    return static_cast<std::uint8_t>(points_.size() < 2 ? 0 : segment_at(s_) + 1);
}

std::optional<StareBegin> PathFollower::step(double dt, Vec3 gimbal_ecef, double pointing_error) {
    const double total = cumulative_.back();
    switch (phase_) {
        case Phase::sweeping:
            s_ = std::min(total, s_ + options_.scan_speed_mps * dt);
            if (s_ >= total) phase_ = Phase::finished;
            return std::nullopt;
        case Phase::finished:
            return std::nullopt;
        case Phase::staring:
            stare_left_ -= dt;
            stare_elapsed_ += dt;
            if (stare_left_ <= 0) end_stare(true);
            return std::nullopt;
        case Phase::stepping:
            break;
    }

    // Stepping toward a station: the cross offset scales with the range, so track it.
    if (cross_index_ == 0) station_range_ = norm(point_at(s_) - gimbal_ecef);
    phase_time_ += dt;
    const bool on_target = pointing_error <= options_.on_target_rad;
    if (!on_target && phase_time_ < options_.step_timeout_s) return std::nullopt;

    StareBegin begin;
    begin.point_ecef = look_point();
    begin.along_track = cross_index_ == 0;
    begin.started_by_time = !on_target;
    begin.prev_terminated_by_time = prev_by_time_;
    begin.max_stare_time_s = options_.stare_time_s;
    begin.prev_stare_time_s = prev_stare_time_;
    begin.stare_load = stared_before_ ? 1.0 : 0.0;  // this gimbal never idles between stares
    begin.cross_angle = cross_offset_angle();
    begin.slant_range_m = norm(begin.point_ecef - gimbal_ecef);
    stared_before_ = true;
    phase_ = Phase::staring;
    stare_left_ = options_.stare_time_s;
    stare_elapsed_ = 0;
    return begin;
}

bool PathFollower::acknowledge() {
    if (phase_ != Phase::staring) return false;
    end_stare(false);
    return true;
}

void PathFollower::end_stare(bool by_time) {
    prev_by_time_ = by_time;
    prev_stare_time_ = std::min(stare_elapsed_, 2.55);
    phase_time_ = 0;
    phase_ = Phase::stepping;
    if (++cross_index_ < stares_per_station()) return;
    cross_index_ = 0;
    const double total = cumulative_.back();
    if (s_ >= total) {
        phase_ = Phase::finished;
        return;
    }
    // Next station one step angle further, as seen from the gimbal; never stand still.
    const double step = std::max(station_range_ * step_.along_step, 1.0);
    s_ = std::min(total, s_ + step);
}

}  // namespace gimbal::sim
