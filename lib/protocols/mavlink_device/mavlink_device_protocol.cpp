#include "protocols/mavlink_device/mavlink_device_protocol.hpp"

#include "command/params.hpp"
#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"
#include "protocols/mavlink_device/mavlink_device_commands.hpp"
#include "protocols/mavlink_device/mavlink_device_stare.hpp"

namespace gimbal::protocols {

namespace {

constexpr double heartbeat_period_s = 1.0;
// GIMBAL_DEVICE_INFORMATION is asked for again this often until it arrives.
constexpr double request_period_s = 2.0;
constexpr std::uint32_t information_id = mavlink::GimbalDeviceInformation::id;
// MAV_TYPE_ONBOARD_CONTROLLER, MAV_AUTOPILOT_INVALID, MAV_STATE_ACTIVE.
constexpr std::uint8_t mav_type_onboard_controller = 18;
constexpr std::uint8_t mav_state_active = 4;
// Decoded payloads only: the session never sees the device's messages as raw bytes.
constexpr std::uint8_t set_attitude_length = mavlink::GimbalDeviceSetAttitude::length;

}  // namespace

MavlinkDeviceProtocol::MavlinkDeviceProtocol(const MavlinkDeviceOptions& options)
    : options_(options),
      signatures_(options.signing_key),
      framer_(signatures_.framer_options()),
      state_(options),
      sender_(options.system_id, options.component_id, options.signing_key) {}

void MavlinkDeviceProtocol::receive(std::span<const std::uint8_t> bytes, double now_s,
                                    std::vector<state::Event>& events,
                                    std::vector<session::Bytes>& replies) {
    framer_.push(bytes, [&](const mavlink::Message& m) {
        if (!signatures_.accept(m, unix_now())) return;  // unsigned, forged or replayed
        const bool had_information = state_.has_information();
        state_.apply(m, now_s);
        if (!had_information && state_.has_information())
            steering_.set_north_yaw(north_yaw_of(state_.cap_flags()));
        if (std::holds_alternative<mavlink::GimbalDeviceAttitudeStatus>(m.payload))
            check_stare(now_s, events);
    });
    // Without a vehicle feed there are no steering ticks: the device's own reports pace the
    // heartbeat and the information request then.
    if (state_.device_system()) housekeeping(now_s, replies);
}

void MavlinkDeviceProtocol::housekeeping(double now_s, std::vector<session::Bytes>& out) {
    if (!last_heartbeat_s_ || now_s - *last_heartbeat_s_ >= heartbeat_period_s) {
        mavlink::Heartbeat hb;
        hb.type = mav_type_onboard_controller;
        hb.autopilot = mavlink::mav_autopilot_invalid;
        hb.system_status = mav_state_active;
        out.push_back(frame(hb));
        last_heartbeat_s_ = now_s;
    }
    if (!state_.has_information() &&
        (!last_request_s_ || now_s - *last_request_s_ >= request_period_s)) {
        out.push_back(request_information());
        last_request_s_ = now_s;
    }
}

void MavlinkDeviceProtocol::tick(double now_s, std::vector<state::Event>& events) {
    state_.tick(now_s, events);
}

session::Bytes MavlinkDeviceProtocol::request_information() {
    mavlink::CommandLong c;
    c.command = mavlink::mav_cmd::request_message;
    c.param[0] = static_cast<float>(information_id);
    c.target_system = state_.device_system().value_or(0);
    c.target_component =
        state_.device_system() ? state_.device_component() : options_.device_component_id;
    return frame(c);
}

std::vector<session::Bytes> MavlinkDeviceProtocol::on_connect() {
    framer_.reset();
    last_request_s_ = std::nullopt;
    return {request_information()};
}

std::optional<mavlink::GimbalDeviceSetAttitude> MavlinkDeviceProtocol::set_attitude(double now_s) {
    std::optional<Aim> aim;
    if (const auto los = state_.line_of_sight()) aim = Aim{*los};
    auto m = steering_.command(state_.vehicle(), state_.camera(), aim, now_s);
    if (!m) return std::nullopt;
    m->target_system = state_.device_system().value_or(0);
    m->target_component =
        state_.device_system() ? state_.device_component() : options_.device_component_id;
    return m;
}

void MavlinkDeviceProtocol::check_stare(double now_s, std::vector<state::Event>& events) {
    if (auto begun = steering_.take_stare_begin()) {
        std::optional<StareView> view;
        const auto camera = state_.camera();
        const auto los = state_.line_of_sight();
        if (const auto& attitude = state_.attitude(); camera && los && attitude)
            view = StareView{*camera, *los, state_.pan_deg(), attitude->pitch_deg,
                             attitude->time_boot_ms};
        auto fields = path_stare_start(*begun, view);
        last_stare_time_ms_ = fields["system_time_ms"].get<std::uint32_t>();
        if (options_.auto_ack_stare)
            if (auto* p = std::get_if<HoldPath>(&steering_.held())) p->follower->acknowledge();
        state_.set_stare(fields);
        events.push_back(state::Event{"stare_start", std::move(fields)});
        return;
    }
    auto* g = std::get_if<HoldGeopoint>(&steering_.held());
    if (!g || !g->stare || g->stared) return;
    const auto camera = state_.camera();
    const auto los = state_.line_of_sight();
    const auto& attitude = state_.attitude();
    if (!camera || !los || !attitude) return;
    auto fields = stare_start(
        geopoint_at(*g, now_s),
        StareView{*camera, *los, state_.pan_deg(), attitude->pitch_deg, attitude->time_boot_ms});
    if (!fields) return;
    g->stared = true;
    last_stare_time_ms_ = (*fields)["system_time_ms"].get<std::uint32_t>();
    state_.set_stare(*fields);
    events.push_back(state::Event{"stare_start", std::move(*fields)});
}

std::size_t MavlinkDeviceProtocol::steer(const vehicle::VehicleState& vehicle, double vehicle_now_s,
                                         double now_s, std::vector<session::Bytes>& out) {
    const auto fix = vehicle::aircraft_fix(vehicle, vehicle_now_s);
    state_.set_vehicle(fix);
    const std::size_t before = out.size();
    feed_vehicle(fix, vehicle_now_s, out);
    const std::size_t fed = out.size() - before;  // AUTOPILOT_STATE_FOR_GIMBAL_DEVICE
    housekeeping(now_s, out);
    if (const auto m = set_attitude(now_s)) out.push_back(frame(*m));
    return fed;
}

void MavlinkDeviceProtocol::feed_vehicle(const std::optional<vehicle::AircraftFix>& fix,
                                         double vehicle_now_s, std::vector<session::Bytes>& out) {
    // At every tick (20 Hz, within the 10-50 Hz devices need for their horizon and yaw
    // estimates); when the fix goes, one message without it so the device stops using the
    // last one.
    if (!fix && !fed_fix_) return;
    fed_fix_ = fix.has_value();
    const auto us = static_cast<std::uint64_t>(vehicle_now_s * 1e6);
    out.push_back(frame(autopilot_state(fix, us, 0, options_.device_component_id)));
}

session::FrameCounters MavlinkDeviceProtocol::counters() const {
    const auto& s = framer_.stats();
    // Refused for signing (unsigned, forged or replayed; or signed while signing is off)
    // count as decode errors, not as packets received.
    const std::uint64_t refused = signatures_.rejected();
    return {s.frames - refused, s.bad_crc, s.dropped_bytes, refused + s.signed_rejected};
}

bool MavlinkDeviceProtocol::supports(std::string_view cmd) const {
    return is_device_command(cmd);
}

std::optional<command::Error> MavlinkDeviceProtocol::plan(std::string_view cmd,
                                                          const nlohmann::json& request,
                                                          const session::Now& now,
                                                          command::Plan& plan) {
    if (cmd == "stare_ack") return acknowledge_stare(request);
    DeviceCommandContext ctx;
    ctx.now_s = now.mono_s;
    ctx.has_vehicle_fix = state_.vehicle().has_value();
    if (ctx.has_vehicle_fix) ctx.vehicle_heading_deg = state_.vehicle()->yaw_deg;
    ctx.geoid_undulation_m = state_.geoid_undulation();
    auto hold = plan_device_command(cmd, request, ctx);
    if (!hold) return hold.error();
    steering_.hold(std::move(hold).value());
    if (const auto m = set_attitude(now.mono_s)) {
        command::WirePacket w;
        w.frame = frame(*m);
        w.sent = {{"id", mavlink::GimbalDeviceSetAttitude::id}, {"len", set_attitude_length}};
        plan.packets.push_back(std::move(w));
    }
    return std::nullopt;
}

std::optional<command::Error> MavlinkDeviceProtocol::acknowledge_stare(
    const nlohmann::json& request) {
    command::JsonParams p(request, "stare_ack");
    const auto time = p.integer("system_time_ms", false);
    p.reject_unknown();
    if (!p.ok()) return p.error();
    if (!time && !last_stare_time_ms_)
        return command::Error{command::code::unavailable,
                              "no stare_start yet: give 'system_time_ms'"};
    const auto echo = time ? static_cast<std::uint32_t>(*time) : *last_stare_time_ms_;
    // As an Orion: an ack that matches no current stare changes nothing.
    if (echo == last_stare_time_ms_)
        if (auto* path = std::get_if<HoldPath>(&steering_.held())) path->follower->acknowledge();
    return std::nullopt;
}

}  // namespace gimbal::protocols
