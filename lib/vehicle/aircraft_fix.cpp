#include "vehicle/aircraft_fix.hpp"

#include <numbers>

namespace gimbal::vehicle {

namespace {

constexpr double rad_to_deg = 180.0 / std::numbers::pi;

}  // namespace

std::optional<AircraftFix> aircraft_fix(const VehicleState& vehicle, double now_s) {
    const auto& pos = vehicle.position();
    const auto& att = vehicle.attitude();
    if (!pos || !att || !vehicle.fresh(now_s)) return std::nullopt;
    if (now_s - pos->at_s > vehicle.timeout_s() || now_s - att->at_s > vehicle.timeout_s())
        return std::nullopt;
    AircraftFix f;
    f.lat_deg = pos->message.lat * 1e-7;
    f.lon_deg = pos->message.lon * 1e-7;
    f.alt_msl_m = pos->message.alt * 1e-3;
    f.vn_mps = pos->message.vx * 0.01;
    f.ve_mps = pos->message.vy * 0.01;
    f.vd_mps = pos->message.vz * 0.01;
    f.roll_deg = att->message.roll * rad_to_deg;
    f.pitch_deg = att->message.pitch * rad_to_deg;
    f.yaw_deg = att->message.yaw * rad_to_deg;
    f.roll_rate_dps = att->message.rollspeed * rad_to_deg;
    f.pitch_rate_dps = att->message.pitchspeed * rad_to_deg;
    f.yaw_rate_dps = att->message.yawspeed * rad_to_deg;
    return f;
}

}  // namespace gimbal::vehicle
