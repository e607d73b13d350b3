// Gimbal pointing: pan/tilt <-> line of sight, and two axes that slew at limited rates.
//
// Convention: the line of sight is the mount x axis turned by pan about the mount z axis
// (down; positive pan turns right), then by tilt about the new y axis (positive tilt looks up).
// Pan 0, tilt -90 deg looks straight down the mount z axis.
#pragma once

#include "sim/frames.hpp"

namespace gimbal::sim {

struct PanTilt {
    double pan = 0;   // rad, [-pi, pi)
    double tilt = 0;  // rad
};

// Unit line of sight in the mount frame.
Vec3 los_in_mount(PanTilt angles);
// The angles whose line of sight is along dir (mount frame, any length). Looking straight
// up or down keeps pan at 0.
PanTilt pan_tilt_for(Vec3 dir_mount);

// Rotation taking mount-frame vectors to ECEF: the mount attitude (mount -> NED) composed with
// the local NED axes at the gimbal.
Mat3 mount_to_ecef(const Quat& mount_to_ned, double lat, double lon);

struct AxisLimits {
    double pan_rate_max = 60 * deg;   // rad/s
    double tilt_rate_max = 60 * deg;  // rad/s
    double tilt_min = -120 * deg;     // rad
    double tilt_max = 30 * deg;       // rad
};

// Two motor axes. Pan turns without end stops; tilt stays within its limits unless a command
// says to ignore them (ORION_MODE_POSITION_NO_LIMITS).
class GimbalAxes {
  public:
    explicit GimbalAxes(AxisLimits limits = {}, PanTilt start = {});

    // Moves toward target for dt seconds at no more than the rate limits; pan takes the
    // shorter way round.
    void slew_toward(PanTilt target, double dt, bool within_limits = true);
    // Moves at the given rates (rad/s, clamped to the rate limits) for dt seconds.
    void move_at(double pan_rate, double tilt_rate, double dt, bool within_limits = true);
    // Motors off: the axes stay where they are.
    void hold() { rates_ = {}; }

    PanTilt angles() const { return angles_; }
    // Angular rates of the last step, rad/s.
    PanTilt rates() const { return rates_; }
    const AxisLimits& limits() const { return limits_; }
    void set_limits(const AxisLimits& limits) { limits_ = limits; }

  private:
    double clamp_tilt(double tilt, bool within_limits) const;

    AxisLimits limits_;
    PanTilt angles_;
    PanTilt rates_;
};

}  // namespace gimbal::sim
