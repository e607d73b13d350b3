// The Orion side of a gimbal session: OrionPublic framer, state model and commands.
#pragma once

#include <memory>

#include "protocols/orion/codec/framer.hpp"
#include "protocols/orion/orion_capabilities.hpp"
#include "protocols/orion/orion_commands.hpp"
#include "protocols/orion/orion_state.hpp"
#include "session/protocol.hpp"

namespace gimbal::protocols {

using session::Bytes;
using session::FrameCounters;
using session::Now;

struct OrionOptions {
    double stale_after_s = 1.0;
    bool auto_ack_stare = false;
    bool allow_fire = false;
    bool allow_safety_bypass = false;
    geo::Surface* terrain = nullptr;  // telemetry's footprint and ground (SessionSettings)
};

class OrionProtocol final : public session::Protocol {
  public:
    explicit OrionProtocol(const OrionOptions& options);

    std::string_view name() const override { return "orion"; }
    void receive(std::span<const std::uint8_t> bytes, double now_s,
                 std::vector<state::Event>& events, std::vector<Bytes>& replies) override;
    void tick(double now_s, std::vector<state::Event>& events) override;
    std::vector<Bytes> on_connect() override;
    bool stale(double now_s) const override { return state_.stale(now_s); }
    std::optional<double> telemetry_age_s(double now_s) const override {
        return state_.telemetry_age_s(now_s);
    }
    std::uint64_t telemetry_count() const override { return state_.telemetry_count(); }
    void write_state(state::JsonWriter& w, const session::StateContext& c) const override;
    FrameCounters counters() const override;
    bool supports(std::string_view cmd) const override;
    const session::Capabilities& capabilities() const override { return capabilities_; }
    const state::Telemetry* telemetry() const override {
        return state_.telemetry() ? &state_.telemetry()->shared : nullptr;
    }
    std::optional<command::Error> plan(std::string_view cmd, const nlohmann::json& request,
                                       const Now& now, command::Plan& plan) override;

    const state::OrionState& state() const { return state_; }

  private:
    OrionOptions options_;
    orion::Framer framer_;
    state::OrionState state_;
    OrionCapabilities capabilities_{state_.data()};
};

}  // namespace gimbal::protocols
