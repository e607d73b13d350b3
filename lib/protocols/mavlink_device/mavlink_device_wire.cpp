#include "protocols/mavlink_device/mavlink_device_wire.hpp"

#include <cmath>

#include "geo/attitude.hpp"

namespace gimbal::protocols {

namespace {
constexpr double rad_to_deg = 180.0 / 3.14159265358979323846;
// ESTIMATOR_STATUS_FLAGS: attitude, horizontal and vertical velocity, absolute position.
constexpr std::uint16_t estimator_valid = 1 | 2 | 4 | 16 | 32;
// MAV_LANDED_STATE_UNDEFINED, _ON_GROUND, _IN_AIR.
constexpr std::uint8_t landed_undefined = 0;
}  // namespace

std::vector<std::uint8_t> MavlinkSender::frame(const mavlink::Payload& payload, double unix_s) {
    if (!key_) return mavlink::encode_v2(payload, system_id_, component_id_, seq_++);
    auto out = mavlink::encode_v2(payload, system_id_, component_id_, seq_++, true);
    mavlink::append_signature(out, *key_, 0, clock_.next(mavlink::signing_timestamp(unix_s)));
    return out;
}

bool SignatureCheck::accept(const mavlink::Message& m, double unix_s) {
    if (!key_) return true;  // the framer delivered an unsigned frame
    const bool ok = m.signature && m.signature->verified &&
                    streams_.accept(m.sysid, m.compid, m.signature->link_id, m.signature->timestamp,
                                    mavlink::signing_timestamp(unix_s));
    if (!ok) ++rejected_;
    return ok;
}

mavlink::AutopilotStateForGimbalDevice autopilot_state(
    const std::optional<vehicle::AircraftFix>& fix, std::uint64_t time_boot_us,
    std::uint8_t target_system, std::uint8_t target_component) {
    mavlink::AutopilotStateForGimbalDevice m;
    m.time_boot_us = time_boot_us;
    m.target_system = target_system;
    m.target_component = target_component;
    m.landed_state = landed_undefined;
    if (!fix) return m;
    const auto q = geo::normalized(
        geo::euler_to_quat(geo::EulerDeg{fix->roll_deg, fix->pitch_deg, fix->yaw_deg}));
    m.q = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
           static_cast<float>(q.z)};
    m.vx = static_cast<float>(fix->vn_mps);
    m.vy = static_cast<float>(fix->ve_mps);
    m.vz = static_cast<float>(fix->vd_mps);
    m.feed_forward_angular_velocity_z = static_cast<float>(fix->yaw_rate_dps / rad_to_deg);
    m.estimator_status = estimator_valid;
    return m;
}

}  // namespace gimbal::protocols
