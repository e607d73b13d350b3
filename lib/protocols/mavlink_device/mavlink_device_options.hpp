// The settings of one MAVLink gimbal device session (contract section 19): the daemon-wide
// ones (SessionSettings) and the gimbal's own `mavlink` object of its configuration.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mavlink/signing.hpp"

#include "geo/surface.hpp"

namespace gimbal::protocols {

struct MavlinkDeviceOptions {
    double stale_after_s = 1.0;
    geo::Surface* terrain = nullptr;  // telemetry's footprint and ground (SessionSettings)
    // Who gimbald is on the device link (the gimbal manager, usually the autopilot's ids).
    std::uint8_t system_id = 1;
    std::uint8_t component_id = 1;
    // The device's component (MAV_COMP_ID_GIMBAL unless it says otherwise).
    std::uint8_t device_component_id = 154;
    // The camera's fields of view when the device reports none (degrees).
    double hfov_deg = 60;
    double vfov_deg = 34;
    // The geoid's height above the ellipsoid where the aircraft flies (metres): the vehicle
    // reports MSL altitudes, STATE and geometry use the ellipsoid.
    double geoid_undulation_m = 0;
    // The flat world where no terrain answers: this altitude above the ellipsoid (metres).
    double ground_alt_m = 0;
    // MAVLink 2 message signing on the device link: the key file's path in the configuration,
    // the key itself once read (make_session), and the UTC clock the signatures carry.
    std::optional<std::string> signing_key_file;
    std::optional<mavlink::SigningKey> signing_key;
    std::function<double()> unix_clock;
};

// From the gimbal's configuration object: its `mavlink` keys over the defaults. Keys of the
// wrong type keep their default (config.cpp has checked them).
MavlinkDeviceOptions read_mavlink_device_options(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
