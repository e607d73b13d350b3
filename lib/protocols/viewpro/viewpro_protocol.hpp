// The Viewpro side of a gimbal session: OUTx framer, state, and the Viewpro commands. On
// every (re)connect it sends the configured mode command so the gimbal starts reporting.
#pragma once

#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/output_framer.hpp"
#include "protocols/viewpro/viewpro_capabilities.hpp"
#include "protocols/viewpro/viewpro_state.hpp"
#include "session/protocol.hpp"

namespace gimbal::protocols {

using session::Bytes;
using session::FrameCounters;
using session::Now;

struct ViewproOptions {
    double stale_after_s = 1.0;
    viewpro::Mode output;  // gimbals[].viewpro.output
};

class ViewproProtocol final : public session::Protocol {
  public:
    explicit ViewproProtocol(const ViewproOptions& options);

    std::string_view name() const override { return "viewpro"; }
    void receive(std::span<const std::uint8_t> bytes, double now_s,
                 std::vector<state::Event>& events, std::vector<Bytes>& replies) override;
    void tick(double now_s, std::vector<state::Event>& events) override;
    std::vector<Bytes> on_connect() override;
    bool stale(double now_s) const override { return state_.stale(now_s); }
    std::optional<double> telemetry_age_s(double now_s) const override {
        return state_.telemetry_age_s(now_s);
    }
    std::uint64_t telemetry_count() const override { return state_.telemetry_count(); }
    void write_state(state::JsonWriter& w, const session::StateContext& c) const override {
        state_.write(w, c.now_s);
    }
    FrameCounters counters() const override;
    bool supports(std::string_view cmd) const override;
    const session::Capabilities& capabilities() const override { return capabilities_; }
    std::optional<command::Error> plan(std::string_view cmd, const nlohmann::json& request,
                                       const Now& now, command::Plan& plan) override;

  private:
    ViewproOptions options_;
    viewpro::OutputFramer framer_;
    state::ViewproState state_;
    ViewproCapabilities capabilities_{state_.output()};
};

}  // namespace gimbal::protocols
