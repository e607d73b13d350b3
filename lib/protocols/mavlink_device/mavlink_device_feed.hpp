// The vehicle feed of a MAVLink gimbal device: AUTOPILOT_STATE_FOR_GIMBAL_DEVICE at every
// feed tick (20 Hz, within the 10-50 Hz devices need for their horizon and yaw estimates)
// while the vehicle's attitude and position are fresh.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "protocols/vehicle_feeder.hpp"

namespace gimbal::protocols {

class MavlinkDeviceFeeder final : public VehicleFeeder {
  public:
    MavlinkDeviceFeeder(std::uint8_t system_id, std::uint8_t component_id,
                        std::uint8_t device_component_id)
        : sender_(system_id, component_id), device_component_id_(device_component_id) {}

    std::string_view kind() const override { return "autopilot_state"; }
    void tick(const vehicle::VehicleState& vehicle, const FeedTime& t,
              std::vector<FeedBytes>& out) override;
    void connection_changed(const vehicle::VehicleState& vehicle, const FeedTime& t,
                            std::vector<FeedBytes>& out) override;

  private:
    MavlinkSender sender_;
    std::uint8_t device_component_id_;
};

// From the gimbal's configuration object (its `mavlink` keys).
std::unique_ptr<VehicleFeeder> make_mavlink_device_feeder(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
