// What a SIYI camera can do, read from its typed state (siyi_state.hpp): point at angles
// (0x0E takes absolute angles), move at rates (0x07), point at locations (gimbald aims it from
// the vehicle's position) and zoom (0x0F, a ratio within the model's range). The line of
// sight is its stabilized pitch with its yaw from the aircraft's heading. Numbers are read
// as STATE shows them.
#pragma once

#include "protocols/siyi/siyi_state.hpp"
#include "session/capabilities.hpp"

namespace gimbal::protocols {

// What every SIYI camera can do (the registry's entry says it without a gimbal).
session::Features siyi_features();

class SiyiCapabilities final : public session::Capabilities {
  public:
    // Bound to `data`, which must outlive it (the session's state).
    explicit SiyiCapabilities(const SiyiData& data) : data_(data) {}

    session::Features features() const override { return siyi_features(); }
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
    const SiyiData& data_;
};

}  // namespace gimbal::protocols
