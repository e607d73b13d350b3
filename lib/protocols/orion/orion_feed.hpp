// The vehicle feed of an Orion (gimbals[].feed {autopilot, gps}): OrionAutopilotData at 1 Hz
// and at once when the feed comes up or is lost, GPS_DATA at 4 Hz when `gps`.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "protocols/vehicle_feeder.hpp"

namespace gimbal::protocols {

class OrionFeeder final : public VehicleFeeder {
  public:
    OrionFeeder(bool autopilot, bool gps) : autopilot_(autopilot), gps_(gps) {}

    std::string_view kind() const override { return "orion"; }
    void tick(const vehicle::VehicleState& vehicle, const FeedTime& t,
              std::vector<FeedBytes>& out) override;
    void connection_changed(const vehicle::VehicleState& vehicle, const FeedTime& t,
                            std::vector<FeedBytes>& out) override;

  private:
    bool autopilot_;
    bool gps_;
};

// From the gimbal's configuration object: its `feed` {autopilot, gps}.
std::unique_ptr<VehicleFeeder> make_orion_feeder(const nlohmann::json& gimbal);

}  // namespace gimbal::protocols
