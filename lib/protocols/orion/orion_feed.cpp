#include "protocols/orion/orion_feed.hpp"

#include "protocols/orion/codec/framing.hpp"
#include "protocols/orion/orion_config.hpp"
#include "protocols/orion/orion_feed_packets.hpp"

namespace gimbal::protocols {

namespace {

constexpr std::uint64_t autopilot_ticks = ticks_per(1.0);  // 1 Hz
constexpr std::uint64_t gps_ticks = ticks_per(0.25);       // 4 Hz

}  // namespace

void OrionFeeder::tick(const vehicle::VehicleState& v, const FeedTime& t,
                       std::vector<FeedBytes>& out) {
    if (autopilot_ && t.tick % autopilot_ticks == 0)
        out.push_back(orion::to_wire(vehicle::orion_autopilot_data(v, t.now_s)));
    if (gps_ && t.tick % gps_ticks == 0)
        if (auto gps = vehicle::orion_gps_data(v, t.now_s, t.unix_s))
            out.push_back(orion::to_wire(*gps));
}

void OrionFeeder::connection_changed(const vehicle::VehicleState& v, const FeedTime& t,
                                     std::vector<FeedBytes>& out) {
    // CommGood changes reach the gimbal at once, not at the next 1 Hz slot.
    if (autopilot_) out.push_back(orion::to_wire(vehicle::orion_autopilot_data(v, t.now_s)));
}

std::unique_ptr<VehicleFeeder> make_orion_feeder(const nlohmann::json& gimbal) {
    const auto c = config::read_checked<OrionConfig>(gimbal);
    return std::make_unique<OrionFeeder>(c.feed_autopilot, c.feed_gps);
}

}  // namespace gimbal::protocols
