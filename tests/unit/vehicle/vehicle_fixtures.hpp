// Builders shared by the vehicle tests: options and MAVLink messages as a sender made them.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "mavlink/mavlink.hpp"
#include "vehicle/vehicle_state.hpp"

namespace vehicle_fixtures {

inline gimbal::vehicle::VehicleOptions options(std::optional<std::uint8_t> system_id = std::nullopt,
                                               double timeout_s = 1.0, std::string source = "") {
    gimbal::vehicle::VehicleOptions o;
    o.system_id = system_id;
    o.timeout_s = timeout_s;
    o.source = std::move(source);
    return o;
}

inline gimbal::mavlink::Message from(std::uint8_t sysid, gimbal::mavlink::Payload payload,
                                     std::uint8_t compid = 1) {
    gimbal::mavlink::Message m;
    m.sysid = sysid;
    m.compid = compid;
    m.msgid = gimbal::mavlink::message_id(payload);
    m.payload = std::move(payload);
    return m;
}

// The aircraft level, heading north, at lat/lon (degrees) and alt_msl_m, heard at now_s.
inline void fix_at(gimbal::vehicle::VehicleState& v, double now_s, double lat = 45.7,
                   double lon = -121.5, double alt_msl_m = 500) {
    gimbal::mavlink::Heartbeat hb;
    hb.system_status = static_cast<std::uint8_t>(gimbal::mavlink::MavState::active);
    v.apply(from(1, hb), now_s);
    v.apply(from(1, gimbal::mavlink::Attitude{}), now_s);
    gimbal::mavlink::GlobalPositionInt pos;
    pos.lat = static_cast<std::int32_t>(std::lround(lat * 1e7));
    pos.lon = static_cast<std::int32_t>(std::lround(lon * 1e7));
    pos.alt = static_cast<std::int32_t>(std::lround(alt_msl_m * 1e3));
    v.apply(from(1, pos), now_s);
}

}  // namespace vehicle_fixtures
