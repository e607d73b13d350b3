#include "protocols/orion/orion_protocol.hpp"

#include "protocols/orion/codec/enums.hpp"
#include "protocols/orion/codec/framing.hpp"

namespace gimbal::protocols {

namespace o = gimbal::orion;

OrionProtocol::OrionProtocol(const OrionOptions& options)
    : options_(options), state_(options.stale_after_s, options.terrain) {}

void OrionProtocol::receive(std::span<const std::uint8_t> bytes, double now_s,
                            std::vector<state::Event>& events, std::vector<Bytes>& replies) {
    framer_.push(bytes, [&](const o::Frame& frame) {
        const std::size_t before = events.size();
        state_.apply(frame, now_s, events);
        if (!options_.auto_ack_stare) return;
        for (std::size_t i = before; i < events.size(); ++i) {
            if (events[i].kind != "stare_start" || !state_.last_stare_time_ms()) continue;
            command::Plan plan;
            const nlohmann::json request{{"system_time_ms", *state_.last_stare_time_ms()}};
            if (!plan_orion("stare_ack", request, {}, plan))
                for (auto& p : plan.packets) replies.push_back(std::move(p.frame));
        }
    });
}

void OrionProtocol::tick(double now_s, std::vector<state::Event>& events) {
    state_.tick(now_s, events);
}

std::vector<Bytes> OrionProtocol::on_connect() {
    framer_.reset();
    // What the Orion SDK and ArduPilot's driver ask for on every connection.
    std::vector<Bytes> out;
    for (const std::uint8_t id :
         {o::pkt::clevis_version, o::pkt::crown_version, o::pkt::payload_version,
          o::pkt::tracker_version, o::pkt::retract_version, o::pkt::lensctl_version,
          o::pkt::cameras, o::pkt::limits})
        out.push_back(o::request_bytes(id));
    return out;
}

void OrionProtocol::write_state(state::JsonWriter& w, const session::StateContext& c) const {
    if (c.lasers)
        state_.write(w, c.now_s, [&](std::uint8_t i) { return c.lasers->firing(i); });
    else
        state_.write(w, c.now_s);
}

FrameCounters OrionProtocol::counters() const {
    const auto& s = framer_.stats();
    return FrameCounters{s.packets, s.bad_checksums, s.dropped_bytes, state_.decode_errors()};
}

bool OrionProtocol::supports(std::string_view cmd) const {
    return command::is_orion_command(cmd);
}

std::optional<command::Error> OrionProtocol::plan(std::string_view cmd,
                                                  const nlohmann::json& request, const Now&,
                                                  command::Plan& plan) {
    command::OrionContext ctx;
    ctx.allow_fire = options_.allow_fire;
    ctx.allow_safety_bypass = options_.allow_safety_bypass;
    if (const auto& t = state_.telemetry()) ctx.geoid_undulation_m = t->packet.geoid_undulation;
    ctx.last_stare_time_ms = state_.last_stare_time_ms();
    return command::plan_orion(cmd, request, ctx, plan);
}

}  // namespace gimbal::protocols
