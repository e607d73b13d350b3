// What an Orion is fed from the vehicle's state (issue 5): OrionAutopilotData and GPS_DATA,
// pure, so the feeder (orion_feed.hpp) only decides when to send. GPS_DATA is nothing when
// the position is missing or older than the vehicle timeout.
#pragma once

#include <optional>

#include "protocols/orion/codec/packets_external.hpp"
#include "protocols/orion/codec/packets_telemetry.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::vehicle {

// OrionAutopilotData: IsFlying (armed and a flying MAV_STATE), CommGood (the feed is fresh),
// Agl (GLOBAL_POSITION_INT relative_alt, -1 when unknown). Always built: a lost feed is
// exactly what CommGood 0 tells the gimbal.
orion::AutopilotData orion_autopilot_data(const VehicleState& state, double now_s);

// GPS_DATA (source mavlinkSource) from GLOBAL_POSITION_INT. GLOBAL_POSITION_INT has neither
// accuracies nor satellites: nominal values are sent, and its MSL altitude is sent as the
// WGS84 height with a zero geoid undulation (no geoid model here). Time from SYSTEM_TIME, else
// `host_unix_s`.
std::optional<orion::GpsData> orion_gps_data(const VehicleState& state, double now_s,
                                             double host_unix_s);

}  // namespace gimbal::vehicle
