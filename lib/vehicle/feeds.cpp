#include "vehicle/feeds.hpp"

#include <algorithm>
#include <cmath>

#include "mavlink/framing.hpp"

namespace gimbal::vehicle {

namespace mav = gimbal::mavlink;

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
