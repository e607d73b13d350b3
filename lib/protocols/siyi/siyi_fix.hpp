// The aircraft as SIYI's steering, telemetry and feed need it: position (MSL), attitude, rates
// and velocity from its autopilot (GLOBAL_POSITION_INT, ATTITUDE), in degrees, metres, m/s.
#pragma once

#include <optional>

#include "vehicle/vehicle_state.hpp"

namespace gimbal::protocols {

struct SiyiFix {
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;
    double roll_rate_dps = 0, pitch_rate_dps = 0, yaw_rate_dps = 0;
    double vn_mps = 0, ve_mps = 0, vd_mps = 0;
};

// The fix when the vehicle state has a fresh position and attitude, else nullopt.
std::optional<SiyiFix> siyi_fix(const vehicle::VehicleState& vehicle, double now_s);

}  // namespace gimbal::protocols
