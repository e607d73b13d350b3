// The aircraft as a gimbal gimbald aims itself needs it (a MAVLink gimbal device, a SIYI
// camera): position (MSL), attitude, rates and velocity from its autopilot's
// GLOBAL_POSITION_INT and ATTITUDE, in degrees, metres, m/s. Pure.
#pragma once

#include <optional>

#include "vehicle/vehicle_state.hpp"

namespace gimbal::vehicle {

struct AircraftFix {
    double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
    double roll_deg = 0, pitch_deg = 0, yaw_deg = 0;
    double roll_rate_dps = 0, pitch_rate_dps = 0, yaw_rate_dps = 0;
    double vn_mps = 0, ve_mps = 0, vd_mps = 0;
};

// The fix when the vehicle state has a fresh position and attitude, else nullopt: nothing is
// better than a stale position.
std::optional<AircraftFix> aircraft_fix(const VehicleState& vehicle, double now_s);

}  // namespace gimbal::vehicle
