// The aircraft's state as read from its autopilot's MAVLink stream (issue 5, the vehicle feed):
// the latest HEARTBEAT, SYSTEM_TIME, ATTITUDE, GLOBAL_POSITION_INT and RC_CHANNELS of one
// vehicle, each with the time it arrived. Pure: every call takes the monotonic time in seconds.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "mavlink/messages.hpp"

namespace gimbal::vehicle {

struct VehicleOptions {
    std::optional<std::uint8_t> system_id;  // nullopt: lock onto the first autopilot heard
    double timeout_s = 1.0;                 // data older than this counts as lost
    std::string source;                     // for STATE: "udp 127.0.0.1:14550", ...
};

// A message and when it arrived (monotonic seconds).
template <class M>
struct Received {
    M message{};
    double at_s = 0;
};

class VehicleState {
  public:
    explicit VehicleState(VehicleOptions options) : options_(std::move(options)) {}

    // Takes one decoded message received at now_s. Returns false when it is ignored: another
    // system, a non-autopilot heartbeat, or anything before the vehicle's system is known.
    bool apply(const mavlink::Message& message, double now_s);

    // True while the vehicle's latest message is at most timeout_s old.
    bool fresh(double now_s) const;
    // Reports a change of fresh(): the new value when it differs from the one reported last
    // (starting from "not connected"), else nullopt. Call it periodically.
    std::optional<bool> connection_change(double now_s);

    // Armed (HEARTBEAT base_mode) and in a flying MAV_STATE (active, critical, emergency).
    bool flying() const;
    // UTC of the vehicle at now_s, from SYSTEM_TIME advanced by its age; nullopt when no
    // SYSTEM_TIME with a time arrived within timeout_s.
    std::optional<double> unix_time_s(double now_s) const;

    // The STATE `vehicle` object (docs/json-api.md, "Vehicle feed").
    nlohmann::json snapshot(double now_s) const;

    std::optional<std::uint8_t> system_id() const { return system_id_; }
    std::uint8_t component_id() const { return component_id_; }
    const std::optional<Received<mavlink::Heartbeat>>& heartbeat() const { return heartbeat_; }
    const std::optional<Received<mavlink::SystemTime>>& system_time() const { return time_; }
    const std::optional<Received<mavlink::Attitude>>& attitude() const { return attitude_; }
    const std::optional<Received<mavlink::GlobalPositionInt>>& position() const {
        return position_;
    }
    const std::optional<Received<mavlink::RcChannels>>& rc_channels() const { return rc_; }
    double timeout_s() const { return options_.timeout_s; }
    std::uint64_t messages() const { return messages_; }
    std::uint64_t ignored() const { return ignored_; }

    // True when `r` arrived within timeout_s of now_s.
    template <class M>
    bool recent(const std::optional<Received<M>>& r, double now_s) const {
        return r && now_s - r->at_s <= options_.timeout_s;
    }

  private:
    bool accepts(const mavlink::Message& message);

    VehicleOptions options_;
    std::optional<std::uint8_t> system_id_;
    std::uint8_t component_id_ = 1;
    std::optional<double> last_s_;
    bool reported_connected_ = false;
    std::optional<Received<mavlink::Heartbeat>> heartbeat_;
    std::optional<Received<mavlink::SystemTime>> time_;
    std::optional<Received<mavlink::Attitude>> attitude_;
    std::optional<Received<mavlink::GlobalPositionInt>> position_;
    std::optional<Received<mavlink::RcChannels>> rc_;
    std::uint64_t messages_ = 0;
    std::uint64_t ignored_ = 0;
};

}  // namespace gimbal::vehicle
