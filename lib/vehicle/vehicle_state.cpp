#include "vehicle/vehicle_state.hpp"

#include <cmath>
#include <numbers>
#include <type_traits>
#include <variant>

#include "calendar/utc.hpp"

namespace gimbal::vehicle {

namespace mav = gimbal::mavlink;

namespace {

constexpr double deg_per_rad = 180.0 / std::numbers::pi;

double round_to(double value, double step) {
    return std::round(value / step) * step;
}

const char* state_name(mav::MavState s) {
    switch (s) {
        case mav::MavState::uninit:
            return "uninit";
        case mav::MavState::boot:
            return "boot";
        case mav::MavState::calibrating:
            return "calibrating";
        case mav::MavState::standby:
            return "standby";
        case mav::MavState::active:
            return "active";
        case mav::MavState::critical:
            return "critical";
        case mav::MavState::emergency:
            return "emergency";
        case mav::MavState::poweroff:
            return "poweroff";
        case mav::MavState::flight_termination:
            return "flight_termination";
    }
    return "unknown";
}

}  // namespace

bool VehicleState::accepts(const mav::Message& message) {
    const auto* hb = std::get_if<mav::Heartbeat>(&message.payload);
    if (options_.system_id) {
        if (message.sysid != *options_.system_id) return false;
        if (hb && !mav::is_autopilot(*hb)) return false;  // a camera or gimbal of that system
        if (hb || !system_id_) component_id_ = message.compid;
        system_id_ = message.sysid;
        return true;
    }
    if (!system_id_) {
        // Lock onto the first flight controller whose heartbeat we hear.
        if (!hb || !mav::is_autopilot(*hb)) return false;
        system_id_ = message.sysid;
        component_id_ = message.compid;
        return true;
    }
    if (message.sysid != *system_id_) return false;
    return !hb || mav::is_autopilot(*hb);
}

bool VehicleState::apply(const mav::Message& message, double now_s) {
    if (!accepts(message)) {
        ++ignored_;
        return false;
    }
    ++messages_;
    last_s_ = now_s;
    std::visit(
        [&]<class M>(const M& m) {
            if constexpr (std::is_same_v<M, mav::Heartbeat>)
                heartbeat_ = Received<M>{m, now_s};
            else if constexpr (std::is_same_v<M, mav::SystemTime>)
                time_ = Received<M>{m, now_s};
            else if constexpr (std::is_same_v<M, mav::Attitude>)
                attitude_ = Received<M>{m, now_s};
            else if constexpr (std::is_same_v<M, mav::GlobalPositionInt>)
                position_ = Received<M>{m, now_s};
            else if constexpr (std::is_same_v<M, mav::RcChannels>)
                rc_ = Received<M>{m, now_s};
        },
        message.payload);
    return true;
}

bool VehicleState::fresh(double now_s) const {
    return last_s_ && now_s - *last_s_ <= options_.timeout_s;
}

std::optional<bool> VehicleState::connection_change(double now_s) {
    const bool now_fresh = fresh(now_s);
    if (now_fresh == reported_connected_) return std::nullopt;
    reported_connected_ = now_fresh;
    return now_fresh;
}

bool VehicleState::flying() const {
    if (!heartbeat_) return false;
    const auto& hb = heartbeat_->message;
    const auto s = mav::system_state(hb);
    return mav::armed(hb) && (s == mav::MavState::active || s == mav::MavState::critical ||
                              s == mav::MavState::emergency);
}

std::optional<double> VehicleState::unix_time_s(double now_s) const {
    if (!recent(time_, now_s) || time_->message.time_unix_usec == 0) return std::nullopt;
    return static_cast<double>(time_->message.time_unix_usec) / 1e6 + (now_s - time_->at_s);
}

nlohmann::json VehicleState::snapshot(double now_s) const {
    using nlohmann::json;
    json out = {{"source", options_.source.empty() ? json(nullptr) : json(options_.source)},
                {"connected", fresh(now_s)},
                {"system_id", system_id_ ? json(*system_id_) : json(nullptr)},
                {"age_s", last_s_ ? json(round_to(now_s - *last_s_, 0.001)) : json(nullptr)},
                {"messages", messages_}};
    if (attitude_) {
        const auto& a = attitude_->message;
        out["attitude"] = {{"roll", round_to(a.roll * deg_per_rad, 1e-4)},
                           {"pitch", round_to(a.pitch * deg_per_rad, 1e-4)},
                           {"yaw", round_to(a.yaw * deg_per_rad, 1e-4)},
                           {"age_s", round_to(now_s - attitude_->at_s, 0.001)}};
    } else {
        out["attitude"] = nullptr;
    }
    if (position_) {
        const auto& p = position_->message;
        out["position"] = {{"lat", p.lat / 1e7},
                           {"lon", p.lon / 1e7},
                           {"alt_msl", p.alt / 1000.0},
                           {"age_s", round_to(now_s - position_->at_s, 0.001)}};
        out["velocity_ned"] = {p.vx / 100.0, p.vy / 100.0, p.vz / 100.0};
        out["relative_alt"] = p.relative_alt / 1000.0;
        out["heading"] =
            p.hdg == mav::GlobalPositionInt::hdg_unknown ? json(nullptr) : json(p.hdg / 100.0);
    } else {
        out["position"] = nullptr;
        out["velocity_ned"] = nullptr;
        out["relative_alt"] = nullptr;
        out["heading"] = nullptr;
    }
    if (heartbeat_) {
        const auto& hb = heartbeat_->message;
        out["armed"] = mav::armed(hb);
        out["flying"] = flying();
        out["system_status"] = state_name(mav::system_state(hb));
    } else {
        out["armed"] = nullptr;
        out["flying"] = nullptr;
        out["system_status"] = nullptr;
    }
    const auto unix_s = unix_time_s(now_s);
    out["time"] =
        unix_s ? json(calendar::to_iso8601(calendar::from_unix_seconds(*unix_s))) : json(nullptr);
    return out;
}

}  // namespace gimbal::vehicle
