#include "protocols/viewpro/viewpro_protocol.hpp"

#include "protocols/viewpro/viewpro_commands.hpp"

namespace gimbal::protocols {

ViewproProtocol::ViewproProtocol(const ViewproOptions& options)
    : options_(options), state_(options.stale_after_s) {}

void ViewproProtocol::receive(std::span<const std::uint8_t> bytes, double now_s,
                              std::vector<state::Event>&, std::vector<Bytes>&) {
    framer_.push(bytes, [&](const viewpro::OutputFrame& frame) { state_.apply(frame, now_s); });
}

void ViewproProtocol::tick(double now_s, std::vector<state::Event>& events) {
    state_.tick(now_s, events);
}

std::vector<Bytes> ViewproProtocol::on_connect() {
    framer_.reset();
    const auto mode = viewpro::encode_mode(options_.output);
    return {Bytes(mode.begin(), mode.end())};
}

FrameCounters ViewproProtocol::counters() const {
    const auto& s = framer_.stats();
    return FrameCounters{s.frames, s.bad_checksums, s.dropped_bytes, state_.decode_errors()};
}

bool ViewproProtocol::supports(std::string_view cmd) const {
    return command::is_viewpro_command(cmd);
}

std::optional<command::Error> ViewproProtocol::plan(std::string_view cmd,
                                                    const nlohmann::json& request, const Now& now,
                                                    command::Plan& plan) {
    return command::plan_viewpro(cmd, request, command::ViewproContext{now.unix_s}, plan);
}

}  // namespace gimbal::protocols
