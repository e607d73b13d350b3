// What gimbald sends on a MAVLink device link: v2 frames from its own system and component,
// with their sequence counter, signed when the link has a key; what it accepts from it; and
// the vehicle's state as the device needs it. Pure: times are passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mavlink/framer.hpp"
#include "mavlink/framing.hpp"
#include "mavlink/messages.hpp"
#include "mavlink/signing.hpp"
#include "vehicle/aircraft_fix.hpp"
#include "vehicle/vehicle_state.hpp"

namespace gimbal::protocols {

class MavlinkSender {
  public:
    // With a key every frame is signed (MAVLink 2 message signing, link id 0).
    MavlinkSender(std::uint8_t system_id, std::uint8_t component_id,
                  std::optional<mavlink::SigningKey> key = std::nullopt)
        : system_id_(system_id), component_id_(component_id), key_(key) {}
    // unix_s: now (UTC), the signed frame's timestamp; unused without a key.
    std::vector<std::uint8_t> frame(const mavlink::Payload& payload, double unix_s = 0);
    // A system without a clock of its own keeps its timestamps ahead of the ones it accepted
    // (the signing guide's rule), so the peer does not take them for replays.
    void follow(std::uint64_t accepted_timestamp) { clock_.raise_to(accepted_timestamp); }

  private:
    std::uint8_t system_id_;
    std::uint8_t component_id_;
    std::optional<mavlink::SigningKey> key_;
    mavlink::SigningClock clock_;
    std::uint8_t seq_ = 0;
};

// What a signed link accepts: with a key, only frames signed with it whose timestamp moves
// its stream forward (a new stream no more than a minute behind the local clock); without
// one, unsigned frames (the framer skips signed ones).
class SignatureCheck {
  public:
    explicit SignatureCheck(std::optional<mavlink::SigningKey> key) : key_(key) {}
    mavlink::FramerOptions framer_options() const {
        return {.accept_signed = key_.has_value(), .signing_key = key_};
    }
    bool accept(const mavlink::Message& m, double unix_s);
    std::uint64_t rejected() const { return rejected_; }
    std::uint64_t latest() const { return streams_.latest(); }

  private:
    std::optional<mavlink::SigningKey> key_;
    mavlink::SigningStreams streams_;
    std::uint64_t rejected_ = 0;
};

// AUTOPILOT_STATE_FOR_GIMBAL_DEVICE for the device from the fix (nullopt: nothing valid,
// the message says so with NaNs and no estimator bits).
mavlink::AutopilotStateForGimbalDevice autopilot_state(
    const std::optional<vehicle::AircraftFix>& fix, std::uint64_t time_boot_us,
    std::uint8_t target_system, std::uint8_t target_component);

}  // namespace gimbal::protocols
