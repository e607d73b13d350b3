// The object's motion in the picture, for predicting where it is while the tracker cannot
// see it: a constant-velocity Kalman filter per axis over the centres of confident boxes
// (pixels, seconds). Prediction coasts on the last velocity. Pure.
#pragma once

#include "track/box.hpp"

namespace gimbal::track {

struct ImageMotionOptions {
    double accel_sigma_px_s2 = 40;  // unmodelled acceleration (turns, the camera's own motion)
    double measure_sigma_px = 1.5;  // a box centre's noise
    double start_speed_sigma_px_s = 100;
};

class ImageMotion {
  public:
    explicit ImageMotion(ImageMotionOptions options = {}) : o_(options) {}

    // Starts at p, at rest (velocity unknown).
    void reset(Point p, double t);
    // Moves to p, keeping the velocity learnt so far (a re-acquired object).
    void relocate(Point p, double t);
    void update(Point p, double t);
    Point predict(double t) const;
    Point velocity() const { return {x_.v, y_.v}; }
    double last_time() const { return t_; }

  private:
    struct Axis {
        double p = 0, v = 0;
        double pp = 0, pv = 0, vv = 0;  // covariance
    };
    void advance(Axis& a, double dt) const;
    void correct(Axis& a, double z) const;

    ImageMotionOptions o_;
    Axis x_, y_;
    double t_ = 0;
};

}  // namespace gimbal::track
