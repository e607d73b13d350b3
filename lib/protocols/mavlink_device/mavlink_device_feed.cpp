#include "protocols/mavlink_device/mavlink_device_feed.hpp"

namespace gimbal::protocols {

std::unique_ptr<VehicleFeeder> make_mavlink_device_feeder(const nlohmann::json&) {
    return std::make_unique<MavlinkDeviceFeeder>();
}

}  // namespace gimbal::protocols
