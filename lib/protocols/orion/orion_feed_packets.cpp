#include "protocols/orion/orion_feed_packets.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "vehicle/feeds.hpp"

namespace gimbal::vehicle {

namespace {

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

}  // namespace gimbal::vehicle
