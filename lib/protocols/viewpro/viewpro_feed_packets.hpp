// What a Viewpro is fed from the vehicle's state (issue 5): IN1/IN2 frames, pure, so the
// feeder (viewpro_feed.hpp) only decides when to send. Nothing when attitude or position is
// missing or older than the vehicle timeout.
#pragma once

#include <optional>

#include "vehicle/feeds.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::vehicle {

enum class ViewproFrame { in1, in2 };
// IN1/IN2 from ATTITUDE and GLOBAL_POSITION_INT (IN2 adds its velocity), UTC time from
// SYSTEM_TIME or else `host_unix_s`.
std::optional<Bytes> viewpro_in(const VehicleState& state, double now_s, double host_unix_s,
                                ViewproFrame frame);

}  // namespace gimbal::vehicle
