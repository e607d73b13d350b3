// The vehicle feed of a Viewpro (gimbals[].feed "in2", "in1" or "mavlink"): IN2 or IN1
// frames, or the vehicle's own MAVLink re-framed, at 10 Hz while the feed is fresh.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "protocols/vehicle_feeder.hpp"
#include "protocols/viewpro/viewpro_config.hpp"

namespace gimbal::protocols {

class ViewproFeeder final : public VehicleFeeder {
  public:
    explicit ViewproFeeder(ViewproFeed frames) : frames_(frames) {}

    std::string_view kind() const override;
    void tick(const vehicle::VehicleState& vehicle, const FeedTime& t,
              std::vector<FeedBytes>& out) override;
    void connection_changed(const vehicle::VehicleState&, const FeedTime&,
                            std::vector<FeedBytes>&) override {}

  private:
    ViewproFeed frames_;
    std::uint8_t mavlink_seq_ = 0;  // the sequence counter of the forwarded MAVLink
};

// From the gimbal's configuration object: its `feed` ("in2" when absent).
std::unique_ptr<VehicleFeeder> make_viewpro_feeder(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
