// What a Viewpro can do, read from its STATE (`output`, the latest OUTx frame): point at
// angles by trimming (viewpro_adjust steps from the reported gimbal angles); no rates,
// no geopoint, no zoom. The line of sight is the aircraft attitude then the gimbal's.
#pragma once

#include "session/capabilities.hpp"

namespace gimbal::protocols {

class ViewproCapabilities final : public session::Capabilities {
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
const ViewproCapabilities& viewpro_capabilities();

}  // namespace gimbal::protocols
