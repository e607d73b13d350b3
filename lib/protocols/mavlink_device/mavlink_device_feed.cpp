#include "protocols/mavlink_device/mavlink_device_feed.hpp"

#include "protocols/mavlink_device/mavlink_device_options.hpp"

namespace gimbal::protocols {

void MavlinkDeviceFeeder::tick(const vehicle::VehicleState& vehicle, const FeedTime& t,
                               std::vector<FeedBytes>& out) {
    const auto fix = vehicle_fix(vehicle, t.now_s);
    if (!fix) return;
    const auto us = static_cast<std::uint64_t>(t.now_s * 1e6);
    out.push_back(sender_.frame(autopilot_state(fix, us, 0, device_component_id_)));
}

void MavlinkDeviceFeeder::connection_changed(const vehicle::VehicleState& vehicle,
                                             const FeedTime& t, std::vector<FeedBytes>& out) {
    // Lost: one message with nothing valid, so the device stops using the last one.
    const auto fix = vehicle_fix(vehicle, t.now_s);
    const auto us = static_cast<std::uint64_t>(t.now_s * 1e6);
    out.push_back(sender_.frame(autopilot_state(fix, us, 0, device_component_id_)));
}

std::unique_ptr<VehicleFeeder> make_mavlink_device_feeder(const nlohmann::json& gimbal) {
    const auto o = read_mavlink_device_options(gimbal);
    return std::make_unique<MavlinkDeviceFeeder>(o.system_id, o.component_id,
                                                 o.device_component_id);
}

}  // namespace gimbal::protocols
