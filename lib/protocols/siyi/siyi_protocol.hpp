// The SIYI side of a gimbal session (docs/siyi.md): gimbald asks the camera who it is
// (0x02, 0x01), for its attitude stream (0x25 at 20 Hz) and laser range stream; it polls its
// zoom, zoom range, recording state and laser target, and asks for the attitude stream again
// while the attitude is late (a camera restarted behind a UDP link has forgotten it). It
// steers with 0x0E/0x07, recomputed at every vehicle-feed tick (steer) for a geopoint or
// path, and tells the camera the aircraft's attitude (0x22) and position (0x3E) from the same
// ticks. One sender numbers every frame (SEQ).
#pragma once

#include <optional>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/siyi_capabilities.hpp"
#include "protocols/siyi/siyi_options.hpp"
#include "protocols/siyi/siyi_state.hpp"
#include "protocols/siyi/siyi_steering.hpp"
#include "session/protocol.hpp"

namespace gimbal::protocols {

class SiyiProtocol final : public session::Protocol {
  public:
    explicit SiyiProtocol(const SiyiOptions& options);

    std::string_view name() const override { return "siyi"; }
    void receive(std::span<const std::uint8_t> bytes, double now_s,
                 std::vector<state::Event>& events, std::vector<session::Bytes>& replies) override;
    void tick(double now_s, std::vector<state::Event>& events) override;
    // The camera sends nothing unasked: the identity, stream and poll requests go out from
    // here too, so a camera that comes up after gimbald (or restarts) is asked again.
    void poll(double now_s, std::vector<session::Bytes>& out) override;
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
        w.json("stare", stare_);
    }
    session::FrameCounters counters() const override;
    bool supports(std::string_view cmd) const override;
    const session::Capabilities& capabilities() const override { return capabilities_; }
    const state::Telemetry* telemetry() const override {
        return state_.telemetry() ? &*state_.telemetry() : nullptr;
    }
    std::optional<command::Error> plan(std::string_view cmd, const nlohmann::json& request,
                                       const session::Now& now, command::Plan& plan) override;

    const SiyiState& state() const { return state_; }
    const SiyiSteering& steering() const { return steering_; }

  private:
    session::Bytes frame(const siyi::ToGimbal& message);
    // The requests due at now_s: who the camera is until it says, and the polled readings.
    void housekeeping(double now_s, std::vector<session::Bytes>& out);
    // A held geopoint with stare: stare_start once the camera's line of sight is on it.
    void check_stare(double now_s, std::vector<state::Event>& events);
    void feed_vehicle(const std::optional<vehicle::AircraftFix>& fix, double vehicle_now_s,
                      std::vector<session::Bytes>& out);

    SiyiOptions options_;
    siyi::Framer framer_;
    SiyiState state_;
    SiyiCapabilities capabilities_{state_.data()};
    SiyiSteering steering_;
    std::uint16_t seq_ = 0;
    std::uint64_t decode_errors_ = 0;
    nlohmann::json stare_ = nullptr;  // STATE `stare`: the latest stare_start's fields
    std::optional<double> last_identity_s_, last_poll_s_, last_gps_s_;
};

}  // namespace gimbal::protocols
