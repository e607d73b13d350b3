#include "track/image_motion.hpp"

namespace gimbal::track {

void ImageMotion::reset(Point p, double t) {
    const double v0 = o_.start_speed_sigma_px_s * o_.start_speed_sigma_px_s;
    const double r = o_.measure_sigma_px * o_.measure_sigma_px;
    x_ = {p.x, 0, r, 0, v0};
    y_ = {p.y, 0, r, 0, v0};
    t_ = t;
}

void ImageMotion::relocate(Point p, double t) {
    advance(x_, t - t_);
    advance(y_, t - t_);
    const double r = o_.measure_sigma_px * o_.measure_sigma_px;
    x_.p = p.x;
    y_.p = p.y;
    x_.pp = y_.pp = r;
    x_.pv = y_.pv = 0;
    t_ = t;
}

void ImageMotion::advance(Axis& a, double dt) const {
    if (dt <= 0) return;
    const double q = o_.accel_sigma_px_s2 * o_.accel_sigma_px_s2;
    a.p += dt * a.v;
    const double pp = a.pp + 2 * dt * a.pv + dt * dt * a.vv + q * dt * dt * dt * dt / 4;
    const double pv = a.pv + dt * a.vv + q * dt * dt * dt / 2;
    const double vv = a.vv + q * dt * dt;
    a.pp = pp;
    a.pv = pv;
    a.vv = vv;
}

void ImageMotion::correct(Axis& a, double z) const {
    const double s = a.pp + o_.measure_sigma_px * o_.measure_sigma_px;
    const double kp = a.pp / s, kv = a.pv / s;
    const double y = z - a.p;
    a.p += kp * y;
    a.v += kv * y;
    const double pp = (1 - kp) * a.pp;
    const double pv = (1 - kp) * a.pv;
    const double vv = a.vv - kv * a.pv;
    a.pp = pp;
    a.pv = pv;
    a.vv = vv;
}

void ImageMotion::update(Point p, double t) {
    advance(x_, t - t_);
    advance(y_, t - t_);
    correct(x_, p.x);
    correct(y_, p.y);
    if (t > t_) t_ = t;
}

Point ImageMotion::predict(double t) const {
    const double dt = t > t_ ? t - t_ : 0;
    return {x_.p + dt * x_.v, y_.p + dt * y_.v};
}

}  // namespace gimbal::track
