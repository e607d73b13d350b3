// The vehicle feed of a MAVLink gimbal device as STATE names it ("autopilot_state"). The
// AUTOPILOT_STATE_FOR_GIMBAL_DEVICE messages themselves go out from the session's steer hook
// (mavlink_device_protocol.hpp) at every feed tick, from the session's one sender: a feeder
// of its own would send as the same system and component with a second sequence counter.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "protocols/vehicle_feeder.hpp"

namespace gimbal::protocols {

class MavlinkDeviceFeeder final : public VehicleFeeder {
  public:
    std::string_view kind() const override { return "autopilot_state"; }
    void tick(const vehicle::VehicleState&, const FeedTime&, std::vector<FeedBytes>&) override {}
    void connection_changed(const vehicle::VehicleState&, const FeedTime&,
                            std::vector<FeedBytes>&) override {}
};

std::unique_ptr<VehicleFeeder> make_mavlink_device_feeder(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
