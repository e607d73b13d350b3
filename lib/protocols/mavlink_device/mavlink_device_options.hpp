// The settings of one MAVLink gimbal device session (contract section 19): the daemon-wide
// ones (SessionSettings) and the gimbal's own `mavlink` object of its configuration.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "mavlink/signing.hpp"
#include "protocols/mavlink_device/mavlink_device_config.hpp"

#include "geo/surface.hpp"

namespace gimbal::protocols {

// The configuration section (mavlink_device_config.hpp) and what the daemon adds at run time.
struct MavlinkDeviceOptions : MavlinkDeviceConfig {
    double stale_after_s = 1.0;
    bool auto_ack_stare = false;      // stare.auto_ack: end each path stare as it begins
    geo::Surface* terrain = nullptr;  // telemetry's footprint and ground (SessionSettings)
    // The EGM96 undulation at a point (SessionSettings::geoid_undulation), asked at the
    // aircraft's position when geoid_undulation_m is not configured; empty: none (0).
    std::function<std::optional<double>(double lat_deg, double lon_deg)> geoid;
    // The signing key once read from signing_key_file (make_session), and the UTC clock the
    // signatures carry.
    std::optional<mavlink::SigningKey> signing_key;
    std::function<double()> unix_clock;
};

// From the gimbal's configuration object as config.cpp wrote it: its `mavlink` keys over the
// defaults.
MavlinkDeviceOptions read_mavlink_device_options(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
