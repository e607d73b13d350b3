// The aircraft carrying the gimbal: a level circle at constant speed, banked for a coordinated
// turn. The gimbal mount is aligned with the aircraft body (x forward, y right, z down).
#pragma once

#include "sim/frames.hpp"

namespace gimbal::sim {

struct PlatformState {
    Lla lla;           // rad, rad, m above the WGS84 ellipsoid
    Vec3 ecef;         // m
    Vec3 vel_ned;      // m/s
    double roll = 0;   // rad
    double pitch = 0;  // rad
    double yaw = 0;    // rad, heading from north
    Quat attitude;     // mount (body) -> NED
};

struct CircleOptions {
    Lla centre{45.7 * deg, -121.5 * deg, 1500.0};
    double radius_m = 1000;
    double speed_mps = 25;     // along the circle; 0 hovers at the centre
    bool clockwise = true;     // seen from above
    double start_bearing = 0;  // rad, bearing of the start point from the centre
};

class CirclePlatform {
  public:
    explicit CirclePlatform(const CircleOptions& options);
    // State t seconds after the start.
    PlatformState at(double t) const;
    const CircleOptions& options() const { return options_; }

  private:
    CircleOptions options_;
    Vec3 centre_ecef_;
    Mat3 centre_ned_to_ecef_;
};

// A platform state from a position and velocity fix (an external GPS feed): level, heading
// along the ground track, or `heading_if_slow` when moving slower than 1 m/s.
PlatformState platform_from_fix(const Lla& position, Vec3 vel_ned, double heading_if_slow);

}  // namespace gimbal::sim
