#include "vehicle/feeds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mavlink/framing.hpp"
#include "protocols/viewpro/codec/input.hpp"

namespace gimbal::vehicle {

namespace mav = gimbal::mavlink;

namespace {

constexpr double deg_per_rad = 180.0 / std::numbers::pi;
constexpr double rad_per_degE7 = std::numbers::pi / 180.0 / 1e7;
constexpr std::uint8_t leap_seconds = 18;  // since 2017

// Nominal accuracies sent in GPS_DATA: GLOBAL_POSITION_INT carries none.
constexpr double nominal_hacc_m = 2.0;
constexpr double nominal_vacc_m = 4.0;
constexpr double nominal_speed_acc_mps = 0.5;
constexpr double nominal_pdop = 1.5;
constexpr std::uint8_t nominal_sats = 10;
constexpr std::uint8_t fix_ok = 0x01;  // uBlox gnssFixOK

}  // namespace

GpsTime gps_time_from_unix(double unix_s, std::uint8_t leap) {
    constexpr double gps_epoch_unix_s = 315964800.0;  // 1980-01-06T00:00:00Z
    constexpr double week_s = 7 * 24 * 3600.0;
    const double gps_s = std::max(0.0, unix_s - gps_epoch_unix_s + leap);
    const double week = std::floor(gps_s / week_s);
    GpsTime t;
    t.week = static_cast<std::uint16_t>(week);
    t.itow_ms = static_cast<std::uint32_t>(std::llround((gps_s - week * week_s) * 1000.0));
    return t;
}

orion::AutopilotData orion_autopilot_data(const VehicleState& state, double now_s) {
    orion::AutopilotData ap;
    ap.comm_good = state.fresh(now_s);
    ap.is_flying = state.flying();
    ap.agl = -1;  // negative: invalid
    if (const auto& p = state.position()) {
        const double agl = std::round(p->message.relative_alt / 1000.0);
        ap.agl = static_cast<std::int16_t>(std::clamp(agl, 0.0, 32767.0));
    }
    return ap;
}

std::optional<orion::GpsData> orion_gps_data(const VehicleState& state, double now_s,
                                             double host_unix_s) {
    if (!state.recent(state.position(), now_s)) return std::nullopt;
    const auto& p = state.position()->message;
    orion::GpsData g;
    g.fix_type = orion::UbloxFixType::three_d_fix;
    g.fix_state = fix_ok;
    g.tracked_sats = nominal_sats;
    g.pdop = nominal_pdop;
    g.lat = p.lat * rad_per_degE7;
    g.lon = p.lon * rad_per_degE7;
    g.alt = p.alt / 1000.0;
    g.vel_ned = {p.vx / 100.0, p.vy / 100.0, p.vz / 100.0};
    g.hacc = nominal_hacc_m;
    g.vacc = nominal_vacc_m;
    g.speed_acc = nominal_speed_acc_mps;
    g.heading_acc = 0;
    const GpsTime t =
        gps_time_from_unix(state.unix_time_s(now_s).value_or(host_unix_s), leap_seconds);
    g.week = t.week;
    g.itow_ms = t.itow_ms;
    g.geoid_undulation = 0;
    g.source = orion::GpsSource::mavlink;
    g.vertical_velocity_valid = true;
    g.leap_seconds = leap_seconds;
    return g;
}

std::optional<Bytes> viewpro_in(const VehicleState& state, double now_s, double host_unix_s,
                                ViewproFrame frame) {
    if (!state.recent(state.attitude(), now_s) || !state.recent(state.position(), now_s))
        return std::nullopt;
    const auto& a = state.attitude()->message;
    const auto& p = state.position()->message;
    viewpro::VehicleInput in;
    in.time = viewpro::from_unix_seconds(state.unix_time_s(now_s).value_or(host_unix_s));
    in.roll_deg = a.roll * deg_per_rad;
    in.pitch_deg = a.pitch * deg_per_rad;
    in.yaw_deg = a.yaw * deg_per_rad;
    in.lat_deg = p.lat / 1e7;
    in.lon_deg = p.lon / 1e7;
    in.alt_msl_m = p.alt / 1000.0;
    if (frame == ViewproFrame::in2)
        in.vel_ned_mps = std::array<double, 3>{p.vx / 100.0, p.vy / 100.0, p.vz / 100.0};
    return viewpro::encode_vehicle(in);
}

Bytes mavlink_forward(const VehicleState& state, double now_s, std::uint8_t& seq) {
    Bytes out;
    if (!state.fresh(now_s) || !state.system_id()) return out;
    const std::uint8_t sysid = *state.system_id();
    const std::uint8_t compid = state.component_id();
    const auto append = [&](const mav::Payload& payload) {
        const auto frame = mav::encode_v1(payload, sysid, compid, seq++);
        out.insert(out.end(), frame.begin(), frame.end());
    };
    if (state.recent(state.attitude(), now_s)) append(state.attitude()->message);
    if (state.recent(state.position(), now_s)) append(state.position()->message);
    if (state.recent(state.system_time(), now_s)) append(state.system_time()->message);
    return out;
}

}  // namespace gimbal::vehicle
