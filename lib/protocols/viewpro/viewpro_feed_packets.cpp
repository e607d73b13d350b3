#include "protocols/viewpro/viewpro_feed_packets.hpp"

#include <array>
#include <numbers>

#include "protocols/viewpro/codec/input.hpp"

namespace gimbal::vehicle {

namespace {

constexpr double deg_per_rad = 180.0 / std::numbers::pi;

}  // namespace

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

}  // namespace gimbal::vehicle
