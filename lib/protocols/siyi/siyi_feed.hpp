// The vehicle feed of a SIYI camera as STATE names it ("aircraft_attitude"). Its 0x22 and
// 0x3E frames go out from the session's steer hook (siyi_protocol.hpp) at every feed tick,
// from the session's one sender: a feeder of its own would number frames with a second SEQ.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "protocols/vehicle_feeder.hpp"

namespace gimbal::protocols {

class SiyiFeeder final : public VehicleFeeder {
  public:
    std::string_view kind() const override { return "aircraft_attitude"; }
    void tick(const vehicle::VehicleState&, const FeedTime&, std::vector<FeedBytes>&) override {}
    void connection_changed(const vehicle::VehicleState&, const FeedTime&,
                            std::vector<FeedBytes>&) override {}
};

inline std::unique_ptr<VehicleFeeder> make_siyi_feeder(const nlohmann::json&) {
    return std::make_unique<SiyiFeeder>();
}

}  // namespace gimbal::protocols
