// A protocol's vehicle-feed hook: what one gimbal is sent from the vehicle's state (issue 5),
// and when. The daemon's VehicleFeed owns the clock and the link; a feeder only says which
// packets are due at each 50 ms tick. Pure.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "vehicle/vehicle_state.hpp"

namespace gimbal::protocols {

using FeedBytes = std::vector<std::uint8_t>;

// The feed ticks every 50 ms: 10 Hz is every 2nd tick, 4 Hz every 5th, 1 Hz every 20th.
inline constexpr double feed_tick_s = 0.05;

// The ticks between two sends of something sent every period_s.
constexpr std::uint64_t ticks_per(double period_s) {
    return static_cast<std::uint64_t>(period_s / feed_tick_s + 0.5);
}

struct FeedTime {
    double now_s = 0;        // the vehicle state's monotonic clock
    double unix_s = 0;       // the host's UTC, for packets that carry time
    std::uint64_t tick = 0;  // ticks since the feed started
};

class VehicleFeeder {
  public:
    virtual ~VehicleFeeder() = default;
    // What STATE `vehicle.feed.kind` calls it (docs/json-api.md, "Vehicle feed").
    virtual std::string_view kind() const = 0;
    // The packets due at this tick.
    virtual void tick(const vehicle::VehicleState& vehicle, const FeedTime& t,
                      std::vector<FeedBytes>& out) = 0;
    // The feed just came up or was lost: what the gimbal must hear at once, not at its next
    // slot.
    virtual void connection_changed(const vehicle::VehicleState& vehicle, const FeedTime& t,
                                    std::vector<FeedBytes>& out) = 0;
};

}  // namespace gimbal::protocols
