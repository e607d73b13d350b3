// What a MAVLink gimbal device can do, read from its STATE (`telemetry` with the Orion's
// derived keys, `device`): point at angles, move at rates and point at locations (gimbald
// aims it); no zoom (a MAVLink camera is another component). The line of sight is the
// device's attitude, its yaw from north or from the aircraft's heading.
#pragma once

#include "session/capabilities.hpp"

namespace gimbal::protocols {

class MavlinkDeviceCapabilities final : public session::Capabilities {
  public:
    session::Features features() const override;
    session::Request point_angles(const nlohmann::json& state,
                                  const session::AnglesTarget& t) const override;
    session::Request rate(const nlohmann::json& state, const session::RateTarget& t) const override;
    session::Request geopoint(const nlohmann::json& state,
                              const session::GeoTarget& t) const override;
    session::Request stop(const nlohmann::json& state) const override;
    session::Request zoom(const nlohmann::json& state, const session::ZoomTarget& t) const override;
    std::optional<geo::Quat> line_of_sight(const nlohmann::json& state) const override;
    session::View view(const nlohmann::json& state) const override;
    command::Result<session::ImageView> image(const nlohmann::json& state) const override;
    std::optional<geo::Quat> platform_attitude(const nlohmann::json& state) const override;
    session::Identity identity(const nlohmann::json& state) const override;
    session::Limits limits(const nlohmann::json& state) const override;
    session::Camera camera(const nlohmann::json& state) const override;
};

// The one instance (capabilities hold no state).
const MavlinkDeviceCapabilities& mavlink_device_capabilities();

}  // namespace gimbal::protocols
