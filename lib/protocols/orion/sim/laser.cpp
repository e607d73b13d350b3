#include "protocols/orion/sim/laser.hpp"

namespace gimbal::sim {

LaserBank::LaserBank(std::vector<orion::LaserType> types, std::string password)
    : password_(std::move(password)) {
    for (auto type : types) {
        LaserUnit unit;
        unit.type = type;
        units_.push_back(unit);
    }
}

LaserResult LaserBank::command(const LaserRequest& request) {
    if (request.index >= units_.size()) return LaserResult::no_such_laser;
    LaserUnit& unit = units_[request.index];
    if (!password_.empty() && request.password != password_) {
        unit.password_lock = true;
        return LaserResult::wrong_password;
    }
    unit.password_lock = false;
    unit.enabled = request.enable;
    unit.armed = request.enable && request.arm;
    unit.active =
        request.fire && unit.enabled && unit.armed && (request.safety_bypass || !locks_.any());
    unit.bypass = request.safety_bypass;
    unit.on_time_ms = request.on_time_ms;
    unit.off_time_ms = request.off_time_ms;
    unit.prf_code = request.prf_code;
    if (request.arm && !unit.armed) return LaserResult::arm_refused;
    if (request.fire && !unit.active) return LaserResult::fire_refused;
    return LaserResult::applied;
}

void LaserBank::set_interlocks(const LaserInterlocks& locks) {
    locks_ = locks;
    for (auto& unit : units_) {
        unit.altitude_lock = locks.altitude;
        unit.ap_comm_lock = locks.ap_comm;
        unit.ap_flying_lock = locks.ap_flying;
        if (locks.any() && !unit.bypass) unit.active = false;
    }
}

}  // namespace gimbal::sim
