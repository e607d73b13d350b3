#include "track/ground/ground_filter.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::track {

namespace {

constexpr double r2d = 180.0 / 3.14159265358979323846;

// Row-major 4x4 helpers: small enough to write out, no library needed.
using Mat4 = std::array<double, 16>;
double& at(Mat4& m, int r, int c) {
    return m[static_cast<std::size_t>(r * 4 + c)];
}

}  // namespace

GroundFilter::GroundFilter(GroundFilterOptions options) : o_(options) {}

void GroundFilter::reset() {
    started_ = false;
    fixes_ = 0;
    rejected_in_row_ = 0;
}

double GroundFilter::fix_sigma(const GroundFix& fix) const {
    return o_.base_sigma_m + o_.sigma_per_km * std::max(0.0, fix.slant_range_m) / 1000.0;
}

std::array<double, 2> GroundFilter::to_local(const geo::Lla& p) const {
    const auto d = geo::ecef_to_ned(geo::lla_to_ecef(p) - reference_ecef_, reference_);
    return {d.x, d.y};
}

geo::Lla GroundFilter::to_geo(double north, double east, double alt) const {
    auto p = geo::ecef_to_lla(reference_ecef_ + geo::ned_to_ecef({north, east, 0}, reference_));
    p.alt_m = alt;
    return p;
}

void GroundFilter::start(const GroundFix& fix) {
    reference_ = fix.position;
    reference_ecef_ = geo::lla_to_ecef(reference_);
    x_ = {0, 0, 0, 0};
    p_ = {};
    const double s = fix_sigma(fix);
    at(p_, 0, 0) = at(p_, 1, 1) = s * s;
    at(p_, 2, 2) = at(p_, 3, 3) = o_.start_speed_sigma * o_.start_speed_sigma;
    alt_ = fix.position.alt_m;
    t_ = fix.t;
    fixes_ = 1;
    rejected_in_row_ = 0;
    started_ = true;
}

void GroundFilter::predict(double dt, Vec4& x, Mat4& p) const {
    if (dt <= 0) return;
    x[0] += dt * x[2];
    x[1] += dt * x[3];
    // P = F P F' with F = [I dt*I; 0 I], then + Q (white acceleration, per axis
    // q * [dt^4/4 dt^3/2; dt^3/2 dt^2]).
    Mat4 fp = p;
    for (int c = 0; c < 4; ++c) {
        at(fp, 0, c) += dt * at(p, 2, c);
        at(fp, 1, c) += dt * at(p, 3, c);
    }
    Mat4 n = fp;
    for (int r = 0; r < 4; ++r) {
        at(n, r, 0) += dt * at(fp, r, 2);
        at(n, r, 1) += dt * at(fp, r, 3);
    }
    const double q = o_.accel_sigma * o_.accel_sigma;
    const double pp = q * dt * dt * dt * dt / 4, pv = q * dt * dt * dt / 2, vv = q * dt * dt;
    for (int axis = 0; axis < 2; ++axis) {
        at(n, axis, axis) += pp;
        at(n, axis, axis + 2) += pv;
        at(n, axis + 2, axis) += pv;
        at(n, axis + 2, axis + 2) += vv;
    }
    p = n;
}

void GroundFilter::rebase() {
    const auto here = to_geo(x_[0], x_[1], alt_);
    reference_ = here;
    reference_ecef_ = geo::lla_to_ecef(here);
    x_[0] = x_[1] = 0;
}

GroundFilter::Outcome GroundFilter::update(const GroundFix& fix) {
    if (!std::isfinite(fix.t) || !std::isfinite(fix.position.lat_deg) ||
        !std::isfinite(fix.position.lon_deg) || !std::isfinite(fix.position.alt_m)) {
        ++rejected_;
        return Outcome::rejected;
    }
    if (!started_) {
        start(fix);
        ++accepted_;
        return Outcome::started;
    }
    const double dt = fix.t - t_;
    if (dt > o_.max_gap_s) {
        start(fix);
        ++accepted_;
        ++restarts_;
        return Outcome::restarted;
    }
    Vec4 x = x_;
    Mat4 p = p_;
    predict(dt, x, p);
    const auto z = to_local(fix.position);
    const double y0 = z[0] - x[0], y1 = z[1] - x[1];
    const double r = fix_sigma(fix) * fix_sigma(fix);
    // S = H P H' + R, the top-left 2x2 plus the fix's noise.
    const double s00 = at(p, 0, 0) + r, s01 = at(p, 0, 1), s10 = at(p, 1, 0), s11 = at(p, 1, 1) + r;
    const double det = s00 * s11 - s01 * s10;
    if (!(det > 0)) {
        ++rejected_;
        return Outcome::rejected;
    }
    const double i00 = s11 / det, i01 = -s01 / det, i10 = -s10 / det, i11 = s00 / det;
    const double d2 = y0 * (i00 * y0 + i01 * y1) + y1 * (i10 * y0 + i11 * y1);
    if (d2 > o_.gate_chi2) {
        ++rejected_;
        // A manoeuvre the constant-velocity model did not expect looks like a run of
        // rejected fixes: widen the spread so the next fix of a real turn gets through,
        // while a lone outlier is still refused.
        for (double& v : p_) v *= o_.reject_inflation;
        if (++rejected_in_row_ >= o_.restart_after) {
            start(fix);
            ++accepted_;
            ++restarts_;
            return Outcome::restarted;
        }
        return Outcome::rejected;
    }
    // K = P H' S^-1 (4x2); x += K y; P = (I - K H) P.
    double k[4][2];
    for (int row = 0; row < 4; ++row) {
        k[row][0] = at(p, row, 0) * i00 + at(p, row, 1) * i10;
        k[row][1] = at(p, row, 0) * i01 + at(p, row, 1) * i11;
    }
    for (int row = 0; row < 4; ++row)
        x[static_cast<std::size_t>(row)] += k[row][0] * y0 + k[row][1] * y1;
    Mat4 np = p;
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c)
            at(np, row, c) -= k[row][0] * at(p, 0, c) + k[row][1] * at(p, 1, c);
    // Keep it symmetric against rounding.
    for (int row = 0; row < 4; ++row)
        for (int c = row + 1; c < 4; ++c)
            at(np, row, c) = at(np, c, row) = 0.5 * (at(np, row, c) + at(np, c, row));
    x_ = x;
    p_ = np;
    const double a = 1 - std::exp(-std::max(0.0, dt) / std::max(1e-3, o_.alt_tau_s));
    alt_ += a * (fix.position.alt_m - alt_);
    t_ = std::max(t_, fix.t);
    ++fixes_;
    ++accepted_;
    rejected_in_row_ = 0;
    if (std::hypot(x_[0], x_[1]) > o_.rebase_m) rebase();
    return Outcome::accepted;
}

std::optional<GroundEstimate> GroundFilter::estimate(double t) const {
    if (!started_) return std::nullopt;
    Vec4 x = x_;
    Mat4 p = p_;
    predict(t - t_, x, p);
    GroundEstimate e;
    e.position = to_geo(x[0], x[1], alt_);
    e.north_mps = x[2];
    e.east_mps = x[3];
    e.speed_mps = std::hypot(x[2], x[3]);
    e.course_deg = std::fmod(std::atan2(x[3], x[2]) * r2d + 360.0, 360.0);
    e.covariance = p;
    e.position_sigma_m = std::sqrt(std::max(at(p, 0, 0), at(p, 1, 1)));
    e.speed_sigma_mps = std::sqrt(std::max(at(p, 2, 2), at(p, 3, 3)));
    e.fixes = fixes_;
    return e;
}

}  // namespace gimbal::track
