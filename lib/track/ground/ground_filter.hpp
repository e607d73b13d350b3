// The object's position and velocity on the ground from the positions its image centre is
// located at, frame after frame (contract section 20): a constant-velocity Kalman filter in
// local north/east metres around a reference point (the first fix, moved along when the
// object has gone far from it), the altitude smoothed apart. A fix's noise grows with the
// slant range it was located at (a pixel covers more ground further away, and the pose's
// angular error grows into metres). Fixes outside the gate (a mislocated frame, a ray that
// met a roof) are rejected and counted; several in a row restart the filter on the newest,
// because then the object really is elsewhere. Time is passed in (seconds, any origin). Pure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "geo/wgs84.hpp"

namespace gimbal::track {

struct GroundFilterOptions {
    double accel_sigma = 1.0;       // m/s^2: unmodelled acceleration (turns, braking)
    double base_sigma_m = 3.0;      // a fix's noise at zero range (m, one sigma per axis)
    double sigma_per_km = 4.0;      // plus this much per km of slant range
    double start_speed_sigma = 25;  // m/s: the velocity's spread before the second fix
    double gate_chi2 = 20;          // squared Mahalanobis distance beyond which a fix is refused
                                    // (2 dof: a true fix lies beyond it once in 22,000)
    double reject_inflation = 1.5;  // the covariance grows so much at each rejected fix
    int restart_after = 5;          // consecutive rejected fixes that restart the filter
    double max_gap_s = 15;          // a fix after a longer gap restarts the filter
    double alt_tau_s = 2.0;         // time constant of the altitude's smoothing
    double rebase_m = 5000;         // move the reference to the object beyond this distance
};

struct GroundFix {
    double t = 0;              // seconds
    geo::Lla position;         // where the image centre of the box was located
    double slant_range_m = 0;  // camera to that point
};

struct GroundEstimate {
    geo::Lla position;
    double north_mps = 0;
    double east_mps = 0;
    double speed_mps = 0;
    double course_deg = 0;  // clockwise from true north, 0..360
    // Covariance of (north m, east m, north m/s, east m/s), row-major.
    std::array<double, 16> covariance{};
    double position_sigma_m = 0;  // sqrt of the larger horizontal position variance
    double speed_sigma_mps = 0;   // the same for velocity
    std::uint64_t fixes = 0;      // accepted since the (re)start
};

class GroundFilter {
  public:
    enum class Outcome { started, accepted, rejected, restarted };

    explicit GroundFilter(GroundFilterOptions options = {});

    Outcome update(const GroundFix& fix);
    // The estimate predicted to time t (>= the last fix; earlier gives the last fix's);
    // nullopt before the first fix. Does not change the filter.
    std::optional<GroundEstimate> estimate(double t) const;
    void reset();

    std::uint64_t accepted() const { return accepted_; }
    std::uint64_t rejected() const { return rejected_; }
    std::uint64_t restarts() const { return restarts_; }
    const GroundFilterOptions& options() const { return o_; }

  private:
    using Vec4 = std::array<double, 4>;
    using Mat4 = std::array<double, 16>;

    void start(const GroundFix& fix);
    void predict(double dt, Vec4& x, Mat4& p) const;
    double fix_sigma(const GroundFix& fix) const;
    std::array<double, 2> to_local(const geo::Lla& p) const;
    geo::Lla to_geo(double north, double east, double alt) const;
    void rebase();

    GroundFilterOptions o_;
    bool started_ = false;
    geo::Lla reference_;
    geo::Vec3 reference_ecef_;
    Vec4 x_{};  // north, east, north velocity, east velocity
    Mat4 p_{};
    double alt_ = 0;
    double t_ = 0;
    std::uint64_t fixes_ = 0;
    int rejected_in_row_ = 0;
    std::uint64_t accepted_ = 0;
    std::uint64_t rejected_ = 0;
    std::uint64_t restarts_ = 0;
};

}  // namespace gimbal::track
