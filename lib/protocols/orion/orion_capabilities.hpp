// What an Orion can do, read from its typed state (orion_state.hpp): pan/tilt positions and
// rates (OrionCmd), geopoints, image geometry from GeolocateTelemetry, zoom as a ratio of the
// first camera's focal lengths, the line of sight from the mount quaternion and pan/tilt, limits
// from LIMITS, identity from the version packets. Numbers are read as STATE shows them (the
// codec's digits), so every answer is the one a client reading STATE would compute.
#pragma once

#include "protocols/orion/orion_state.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

// What every Orion can do (the registry's entry says it without a gimbal).
session::Features orion_features();

class OrionCapabilities final : public session::Capabilities {
  public:
    // Bound to `data`, which must outlive it (the session's state).
    explicit OrionCapabilities(const state::OrionData& data) : data_(data) {}

    session::Features features() const override { return orion_features(); }
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
    std::optional<bool> holds_geopoint() const override;

  private:
    const state::Telemetry* shared() const;
    std::optional<geo::Quat> mount() const;

    const state::OrionData& data_;
};

}  // namespace gimbal::protocols
