// What a Viewpro can do, read from its latest OUTx frame (viewpro_state.hpp): point at angles
// by stepping from the reported ones (viewpro_adjust); no rates, geopoints or zoom. The line of
// sight is the aircraft's attitude (output.uav) then the gimbal's relative to it
// (output.gimbal); OUTx frames carry no field of view, so there is no image geometry.
#pragma once

#include <optional>

#include "protocols/viewpro/codec/output.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

// What every Viewpro can do (the registry's entry says it without a gimbal).
session::Features viewpro_features();

class ViewproCapabilities final : public session::Capabilities {
  public:
    // Bound to `output` (the latest frame, nullopt before the first), which must outlive it.
    explicit ViewproCapabilities(const std::optional<viewpro::Output>& output) : output_(output) {}

    session::Features features() const override { return viewpro_features(); }
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
    const std::optional<viewpro::Output>& output_;
};

}  // namespace gimbal::protocols
