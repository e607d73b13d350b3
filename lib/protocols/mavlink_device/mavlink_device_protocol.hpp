// The MAVLink gimbal device side of a gimbal session (contract section 19): gimbald is the
// device's gimbal manager. It asks for GIMBAL_DEVICE_INFORMATION, reads
// GIMBAL_DEVICE_ATTITUDE_STATUS, and steers with GIMBAL_DEVICE_SET_ATTITUDE, recomputed at
// every vehicle-feed tick (steer) from what it holds the device to. The same ticks carry
// AUTOPILOT_STATE_FOR_GIMBAL_DEVICE and a heartbeat once a second (with the device's reports
// when there is no vehicle feed): everything gimbald sends the device comes from one sender,
// so its sequence numbers count every frame of the component, as receivers expect.
#pragma once

#include "mavlink/framer.hpp"
#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"
#include "protocols/mavlink_device/mavlink_device_options.hpp"
#include "protocols/mavlink_device/mavlink_device_state.hpp"
#include "protocols/mavlink_device/mavlink_device_steering.hpp"
#include "protocols/mavlink_device/mavlink_device_wire.hpp"
#include "session/protocol.hpp"

namespace gimbal::protocols {

class MavlinkDeviceProtocol final : public session::Protocol {
  public:
    explicit MavlinkDeviceProtocol(const MavlinkDeviceOptions& options);

    std::string_view name() const override { return "mavlink"; }
    void receive(std::span<const std::uint8_t> bytes, double now_s,
                 std::vector<state::Event>& events, std::vector<session::Bytes>& replies) override;
    void tick(double now_s, std::vector<state::Event>& events) override;
    std::size_t steer(const vehicle::VehicleState& vehicle, double vehicle_now_s, double now_s,
                      std::vector<session::Bytes>& out) override;
    std::vector<session::Bytes> on_connect() override;
    bool stale(double now_s) const override { return state_.stale(now_s); }
    std::optional<double> telemetry_age_s(double now_s) const override {
        return state_.telemetry_age_s(now_s);
    }
    std::uint64_t telemetry_count() const override { return state_.telemetry_count(); }
    void write_state(state::JsonWriter& w, const session::StateContext& c) const override {
        state_.write(w, c.now_s);
    }
    session::FrameCounters counters() const override;
    bool supports(std::string_view cmd) const override;
    const session::Capabilities& capabilities() const override { return capabilities_; }
    const state::Telemetry* telemetry() const override {
        return state_.telemetry() ? &*state_.telemetry() : nullptr;
    }
    std::optional<command::Error> plan(std::string_view cmd, const nlohmann::json& request,
                                       const session::Now& now, command::Plan& plan) override;

    const MavlinkDeviceState& state() const { return state_; }
    const MavlinkDeviceSteering& steering() const { return steering_; }

  private:
    session::Bytes request_information();
    // The heartbeat (1 Hz) and, until it arrives, the information request (every 2 s).
    void housekeeping(double now_s, std::vector<session::Bytes>& out);
    std::optional<mavlink::GimbalDeviceSetAttitude> set_attitude(double now_s);
    // A held geopoint with stare: stare_start once the device's line of sight is on it.
    void check_stare(double now_s, std::vector<state::Event>& events);
    // stare_ack: the Orion's StareAck, kept by gimbald (a device has no step-stare of its
    // own): a matching system_time_ms ends the current stare of a held path.
    std::optional<command::Error> acknowledge_stare(const nlohmann::json& request);
    double unix_now() const { return options_.unix_clock ? options_.unix_clock() : 0.0; }
    session::Bytes frame(const mavlink::Payload& payload) {
        return sender_.frame(payload, unix_now());
    }
    // AUTOPILOT_STATE_FOR_GIMBAL_DEVICE while the vehicle's fix is fresh, and once with
    // nothing valid when it goes.
    void feed_vehicle(const std::optional<vehicle::AircraftFix>& fix, double vehicle_now_s,
                      std::vector<session::Bytes>& out);

    MavlinkDeviceOptions options_;
    SignatureCheck signatures_;  // before framer_: it configures it
    mavlink::Framer framer_;
    MavlinkDeviceState state_;
    MavlinkDeviceCapabilities capabilities_{state_.data()};
    MavlinkDeviceSteering steering_;
    MavlinkSender sender_;
    std::optional<double> last_heartbeat_s_;
    std::optional<std::uint32_t> last_stare_time_ms_;  // the latest stare_start's
    std::optional<double> last_request_s_;
    bool fed_fix_ = false;  // the last AUTOPILOT_STATE carried a valid fix
};

}  // namespace gimbal::protocols
