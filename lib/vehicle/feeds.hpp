// What each gimbal is fed from the vehicle's state (issue 5): pure builders of wire bytes, so
// the daemon only decides when to send. Each returns nothing when the data it needs is
// missing or older than the vehicle timeout: nothing is better than a stale position.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "protocols/orion/codec/packets_external.hpp"
#include "protocols/orion/codec/packets_telemetry.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::vehicle {

using Bytes = std::vector<std::uint8_t>;

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

enum class ViewproFrame { in1, in2 };
// IN1/IN2 from ATTITUDE and GLOBAL_POSITION_INT (IN2 adds its velocity), UTC time from
// SYSTEM_TIME or else `host_unix_s`.
std::optional<Bytes> viewpro_in(const VehicleState& state, double now_s, double host_unix_s,
                                ViewproFrame frame);

// ATTITUDE, GLOBAL_POSITION_INT and SYSTEM_TIME re-encoded as MAVLink v1 frames (as a
// Pixhawk's SRx_EXTRA1/SRx_POSITION streams carry them), with the vehicle's system and
// component ids; `seq` is the sequence counter of this output, advanced per frame. Only the
// messages received within the timeout; nothing when the feed is lost.
Bytes mavlink_forward(const VehicleState& state, double now_s, std::uint8_t& seq);

// GPS week and time of week of a UTC time (GPS time counts the leap seconds UTC skips).
struct GpsTime {
    std::uint16_t week = 0;
    std::uint32_t itow_ms = 0;
};
GpsTime gps_time_from_unix(double unix_s, std::uint8_t leap_seconds);

}  // namespace gimbal::vehicle
