// Builders shared by the vehicle tests: options and MAVLink messages as a sender made them.
#pragma once

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

}  // namespace vehicle_fixtures
