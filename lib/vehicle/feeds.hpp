// What any gimbal may be fed from the vehicle's state (issue 5): pure builders of wire bytes,
// so the daemon only decides when to send; a protocol's own packets are built in its home
// (protocols/<name>/<name>_feed_packets.hpp). Each returns nothing when the data it needs is
// missing or older than the vehicle timeout: nothing is better than a stale position.
#pragma once

#include <cstdint>
#include <vector>

#include "vehicle/vehicle_state.hpp"

namespace gimbal::vehicle {

using Bytes = std::vector<std::uint8_t>;

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
