#include "protocols/siyi/siyi_protocol.hpp"

#include <numbers>

#include "protocols/siyi/siyi_commands.hpp"
#include "protocols/siyi/siyi_stare.hpp"

namespace gimbal::protocols {

namespace {

constexpr double deg_to_rad = std::numbers::pi / 180.0;
// The hardware id and firmware are asked for again this often until they arrive (firmware
// reads 0.0.0 for up to 30 s after power-on: docs/siyi.md).
constexpr double identity_period_s = 2.0;
// Zoom, zoom range, recording state and the laser's target, which the camera does not push.
constexpr double poll_period_s = 0.5;
// 0x3E: position changes slowly against 0x22's attitude, which goes at every tick (20 Hz,
// the SDK's 20-50 Hz).
constexpr double gps_period_s = 0.2;
// An attitude this late means the stream stopped: a camera that restarted behind a UDP link
// (no connection to lose) has forgotten it.
constexpr double attitude_late_s = 0.5;

siyi::DataStreamRequest attitude_stream() {
    return {siyi::StreamType::attitude, siyi::StreamRate::hz20};
}

}  // namespace

SiyiProtocol::SiyiProtocol(const SiyiOptions& options) : options_(options), state_(options) {}

session::Bytes SiyiProtocol::frame(const siyi::ToGimbal& message) {
    return siyi::encode(message, siyi::Header{siyi::ctrl_need_ack, seq_++});
}

void SiyiProtocol::receive(std::span<const std::uint8_t> bytes, double now_s,
                           std::vector<state::Event>& events,
                           std::vector<session::Bytes>& replies) {
    bool heard = false;
    framer_.push(bytes, [&](const siyi::Frame& f) {
        const auto decoded = siyi::decode_from_gimbal(f);
        if (!decoded) {
            ++decode_errors_;
            return;
        }
        state_.apply(decoded.value, now_s);
        heard = true;
        if (std::holds_alternative<siyi::GimbalAttitude>(decoded.value)) check_stare(now_s, events);
    });
    // The camera's frames pace the requests and a rate's impulse at its own rate (20 Hz);
    // poll() does at 10 Hz when it is silent.
    if (!heard) return;
    housekeeping(now_s, replies);
    if (const auto stop = steering_.expire(now_s)) replies.push_back(frame(*stop));
}

void SiyiProtocol::housekeeping(double now_s, std::vector<session::Bytes>& out) {
    const SiyiData& d = state_.data();
    const bool firmware_known = d.firmware && d.firmware->gimbal != "0.0.0";
    if ((!d.hardware_id || !firmware_known) &&
        (!last_identity_s_ || now_s - *last_identity_s_ >= identity_period_s)) {
        if (!d.hardware_id) out.push_back(frame(siyi::HardwareIdRequest{}));
        if (!firmware_known) out.push_back(frame(siyi::FirmwareVersionRequest{}));
        last_identity_s_ = now_s;
    }
    if (!last_poll_s_ || now_s - *last_poll_s_ >= poll_period_s) {
        if (!d.attitude || now_s - d.attitude->received_s > attitude_late_s)
            out.push_back(frame(attitude_stream()));
        out.push_back(frame(siyi::CurrentZoomRequest{}));
        out.push_back(frame(siyi::CameraSystemInfoRequest{}));
        if (!d.zoom_max) out.push_back(frame(siyi::ZoomRangeRequest{}));
        if (state_.model().has_laser) out.push_back(frame(siyi::LaserTargetRequest{}));
        last_poll_s_ = now_s;
    }
}

void SiyiProtocol::check_stare(double now_s, std::vector<state::Event>& events) {
    auto* g = std::get_if<SiyiHoldGeopoint>(&steering_.held());
    if (!g || !g->stare || g->stared) return;
    const auto camera = state_.camera();
    const auto los = state_.line_of_sight();
    const auto& attitude = state_.data().attitude;
    if (!camera || !los || !attitude) return;
    const SiyiStareView view{*camera, *los, attitude->pan_deg, attitude->tilt_deg,
                             static_cast<std::uint32_t>(now_s * 1000.0)};
    auto fields = siyi_stare_start(siyi_geopoint_at(*g, now_s), view);
    if (!fields) return;
    g->stared = true;
    stare_ = *fields;
    events.push_back(state::Event{"stare_start", std::move(*fields)});
}

void SiyiProtocol::tick(double now_s, std::vector<state::Event>& events) {
    state_.tick(now_s, events);
}

void SiyiProtocol::poll(double now_s, std::vector<session::Bytes>& out) {
    housekeeping(now_s, out);
    if (const auto stop = steering_.expire(now_s)) out.push_back(frame(*stop));
}

std::vector<session::Bytes> SiyiProtocol::on_connect() {
    framer_.reset();
    last_identity_s_ = last_poll_s_ = std::nullopt;
    std::vector<session::Bytes> out;
    out.push_back(frame(siyi::HardwareIdRequest{}));
    out.push_back(frame(siyi::FirmwareVersionRequest{}));
    out.push_back(frame(attitude_stream()));
    // The laser stream goes at the rangefinder's own rate; a camera without one stays silent.
    out.push_back(
        frame(siyi::DataStreamRequest{siyi::StreamType::laser_range, siyi::StreamRate::hz10}));
    out.push_back(frame(siyi::ZoomRangeRequest{}));
    return out;
}

void SiyiProtocol::feed_vehicle(const std::optional<vehicle::AircraftFix>& fix,
                                double vehicle_now_s, std::vector<session::Bytes>& out) {
    if (!fix) return;
    const auto ms = static_cast<std::uint32_t>(vehicle_now_s * 1000.0);
    const auto rad = [](double d) { return static_cast<float>(d * deg_to_rad); };
    out.push_back(frame(siyi::AircraftAttitude{ms, rad(fix->roll_deg), rad(fix->pitch_deg),
                                               rad(fix->yaw_deg), rad(fix->roll_rate_dps),
                                               rad(fix->pitch_rate_dps), rad(fix->yaw_rate_dps)}));
    if (last_gps_s_ && vehicle_now_s - *last_gps_s_ < gps_period_s && vehicle_now_s >= *last_gps_s_)
        return;
    last_gps_s_ = vehicle_now_s;
    siyi::RawGps g;
    g.time_boot_ms = ms;
    g.lat = fix->lat_deg;
    g.lon = fix->lon_deg;
    g.alt_msl = fix->alt_msl_m;
    g.alt_ellipsoid = fix->alt_msl_m + state_.geoid_undulation();
    g.vn = fix->vn_mps;
    g.ve = fix->ve_mps;
    g.vd = fix->vd_mps;
    out.push_back(frame(g));
}

std::size_t SiyiProtocol::steer(const vehicle::VehicleState& vehicle, double vehicle_now_s,
                                double now_s, std::vector<session::Bytes>& out) {
    const auto fix = vehicle::aircraft_fix(vehicle, vehicle_now_s);
    state_.set_vehicle(fix);
    const std::size_t before = out.size();
    feed_vehicle(fix, vehicle_now_s, out);
    const std::size_t fed = out.size() - before;
    housekeeping(now_s, out);
    if (const auto m = steering_.command(fix, state_.camera(), state_.line_of_sight(), now_s))
        out.push_back(frame(*m));
    return fed;
}

session::FrameCounters SiyiProtocol::counters() const {
    const auto& s = framer_.stats();
    return {s.frames, s.bad_checksums, s.dropped_bytes, decode_errors_};
}

bool SiyiProtocol::supports(std::string_view cmd) const {
    return is_siyi_command(cmd);
}

std::optional<command::Error> SiyiProtocol::plan(std::string_view cmd,
                                                 const nlohmann::json& request,
                                                 const session::Now& now, command::Plan& plan) {
    SiyiCommandContext ctx;
    ctx.now_s = now.mono_s;
    ctx.has_vehicle_fix = state_.vehicle().has_value();
    if (ctx.has_vehicle_fix) ctx.vehicle_yaw_deg = state_.vehicle()->yaw_deg;
    ctx.geoid_undulation_m = state_.geoid_undulation();
    ctx.model = &state_.model();
    auto planned = plan_siyi_command(cmd, request, ctx);
    if (!planned) return planned.error();
    const auto add = [&](const siyi::ToGimbal& m) {
        command::WirePacket w;
        w.frame = frame(m);
        w.sent = {{"cmd_id", siyi::command_of(m)},
                  {"message", siyi::name_of(m)},
                  {"len", w.frame.size()}};
        plan.packets.push_back(std::move(w));
    };
    for (const auto& m : planned->send) add(m);
    if (planned->hold) {
        steering_.hold(*planned->hold);
        // A location is aimed at once, not at the next tick.
        if (const auto m = steering_.command(state_.vehicle(), state_.camera(),
                                             state_.line_of_sight(), now.mono_s);
            m && planned->send.empty())
            add(*m);
    }
    return std::nullopt;
}

}  // namespace gimbal::protocols
