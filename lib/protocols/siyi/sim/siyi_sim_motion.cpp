#include "protocols/siyi/sim/siyi_sim_motion.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::siyi {

namespace {

double toward(double from, double to, double max_step) {
    return from + std::clamp(to - from, -max_step, max_step);
}

}  // namespace

SimMotion::SimMotion(const ModelInfo& model, double yaw, double pitch, double zoom)
    : model_(model),
      yaw_(0),
      pitch_(0),
      zoom_(std::clamp(zoom, 1.0, model.zoom_max)),
      target_zoom_(zoom_) {
    yaw_ = clamp_yaw(yaw);
    pitch_ = clamp_pitch(pitch);
}

double SimMotion::clamp_yaw(double yaw) const {
    if (!std::isfinite(yaw)) return yaw_;
    if (model_.yaw_continuous) return wrap180(yaw);
    return std::clamp(yaw, model_.yaw_min, model_.yaw_max);
}

double SimMotion::clamp_pitch(double pitch) const {
    if (!std::isfinite(pitch)) return pitch_;
    return std::clamp(pitch, model_.pitch_min, model_.pitch_max);
}

void SimMotion::go_to(double yaw, double pitch) {
    drive_ = Drive::angles;
    target_yaw_ = clamp_yaw(yaw);
    target_pitch_ = clamp_pitch(pitch);
}

void SimMotion::turn(std::int8_t turn_yaw, std::int8_t turn_pitch) {
    const auto speed = [&](std::int8_t pct) {
        return std::clamp(static_cast<double>(pct), -100.0, 100.0) / 100.0 * model_.max_rate_dps;
    };
    speed_yaw_ = -speed(turn_yaw);  // turning right lowers SIYI's left-positive yaw
    speed_pitch_ = speed(turn_pitch);
    drive_ = (turn_yaw == 0 && turn_pitch == 0) ? Drive::hold : Drive::speeds;
}

void SimMotion::zoom_to(double zoom) {
    if (std::isfinite(zoom)) target_zoom_ = std::clamp(zoom, 1.0, model_.zoom_max);
}

void SimMotion::zoom_step(ZoomStep s) {
    switch (s) {
        case ZoomStep::in:
            target_zoom_ = model_.zoom_max;
            break;
        case ZoomStep::out:
            target_zoom_ = 1.0;
            break;
        case ZoomStep::stop:
            target_zoom_ = zoom_;
            break;
    }
}

void SimMotion::step(double dt) {
    if (!(dt > 0)) return;
    const double yaw_before = yaw_, pitch_before = pitch_;
    const double max_move = model_.max_rate_dps * dt;
    switch (drive_) {
        case Drive::hold:
            break;
        case Drive::angles: {
            const double dyaw =
                model_.yaw_continuous ? wrap180(target_yaw_ - yaw_) : target_yaw_ - yaw_;
            yaw_ = clamp_yaw(yaw_ + std::clamp(dyaw, -max_move, max_move));
            pitch_ = toward(pitch_, target_pitch_, max_move);
            if (yaw_ == target_yaw_ && pitch_ == target_pitch_) drive_ = Drive::hold;
            break;
        }
        case Drive::speeds:
            yaw_ = clamp_yaw(yaw_ + speed_yaw_ * dt);
            pitch_ = clamp_pitch(pitch_ + speed_pitch_ * dt);
            break;
    }
    const double dyaw = model_.yaw_continuous ? wrap180(yaw_ - yaw_before) : yaw_ - yaw_before;
    yaw_rate_ = dyaw / dt;
    pitch_rate_ = (pitch_ - pitch_before) / dt;

    // The lens covers ln(zoom_max) in zoom_traverse_s, in either direction.
    if (zoom_ != target_zoom_) {
        const double span = std::log(model_.zoom_max);
        const double max_log_step =
            model_.zoom_traverse_s > 0 ? span / model_.zoom_traverse_s * dt : span;
        const double next = toward(std::log(zoom_), std::log(target_zoom_), max_log_step);
        zoom_ = std::abs(next - std::log(target_zoom_)) < 1e-12 ? target_zoom_ : std::exp(next);
    }
}

}  // namespace gimbal::siyi
