// What a MAVLink gimbal device can do, read from its typed state (mavlink_device_state.hpp:
// the shared telemetry with the Orion's derived keys, its information and attitude): point at
// angles, move at rates and point at locations (gimbald aims it); no zoom (a MAVLink camera is
// another component). The line of sight is the device's attitude, its yaw from north or from
// the aircraft's heading. Numbers are read as STATE shows them.
#pragma once

#include "protocols/mavlink_device/mavlink_device_state.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

// What every MAVLink gimbal device can do (the registry's entry says it without a gimbal).
session::Features mavlink_device_features();

class MavlinkDeviceCapabilities final : public session::Capabilities {
  public:
    // Bound to `data`, which must outlive it (the session's state).
    explicit MavlinkDeviceCapabilities(const MavlinkDeviceData& data) : data_(data) {}

    session::Features features() const override { return mavlink_device_features(); }
    session::Request point_angles(const session::AnglesTarget& t) const override;
    session::Request rate(const session::RateTarget& t) const override;
    session::Request geopoint(const session::GeoTarget& t) const override;
    session::Request stop() const override;
    session::Request zoom(const session::ZoomTarget& t) const override;
    std::optional<geo::Quat> line_of_sight() const override;
    session::View view() const override;
    command::Result<session::ImageView> image() const override;
    std::optional<geo::Quat> platform_attitude() const override;
    session::Identity identity() const override;
    session::Limits limits() const override;
    session::Camera camera() const override;

  private:
    const MavlinkDeviceData& data_;
};

}  // namespace gimbal::protocols
