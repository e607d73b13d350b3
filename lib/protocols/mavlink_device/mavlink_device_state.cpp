#include "protocols/mavlink_device/mavlink_device_state.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "geo/ground.hpp"
#include "geo/wgs84.hpp"
#include "protocols/mavlink_device/mavlink_device_flags.hpp"
#include "session/aimed_telemetry.hpp"
#include "session/capabilities.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using state::angle_deg;
using state::latlon_deg;
using state::metres;

namespace {

constexpr double rad_to_deg = 180.0 / 3.14159265358979323846;

}  // namespace

// A limit outside -360..360 degrees, or a pair whose min exceeds its max, is unknown (null)
// and is not relayed (contract section 14, v4): a device's +-5.7e39 would reach every ground
// station as GIMBAL_MANAGER_INFORMATION.
std::pair<std::optional<double>, std::optional<double>> device_limits(float min_rad,
                                                                      float max_rad) {
    const auto sane = [](float rad) -> std::optional<double> {
        if (!std::isfinite(rad) || std::abs(rad * rad_to_deg) > 360.0) return std::nullopt;
        return rad * rad_to_deg;
    };
    auto min = sane(min_rad);
    auto max = sane(max_rad);
    if (min && max && min_rad > max_rad) min = max = std::nullopt;
    return {min, max};
}

// A fixed-size, possibly unterminated char[32] of the wire.
std::string device_text(const std::array<std::uint8_t, 32>& chars) {
    std::string s;
    for (const auto c : chars) {
        if (c == 0) break;
        s.push_back(c >= 0x20 && c < 0x7F ? static_cast<char>(c) : '?');
    }
    return s;
}

// common.xml: (Dev & 0xff) << 24 + (Patch & 0xff) << 16 + (Minor & 0xff) << 8 + (Major & 0xff),
// shown as "Major.Minor.Patch", with ".Dev" only for a development build (Dev not 0).
std::string firmware_text(std::uint32_t v) {
    std::string text = std::to_string(v & 0xFF) + "." + std::to_string((v >> 8) & 0xFF) + "." +
                       std::to_string((v >> 16) & 0xFF);
    if ((v >> 24) != 0) text += "." + std::to_string(v >> 24);
    return text;
}

namespace {

double radians_per_second(float v) {
    return std::isfinite(v) ? v * rad_to_deg : 0.0;
}

}  // namespace

std::optional<geo::EulerDeg> euler_of(const std::array<float, 4>& q) {
    for (const float c : q)
        if (!std::isfinite(c)) return std::nullopt;
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) return std::nullopt;
    return geo::quat_to_euler(geo::Quat{q[0], q[1], q[2], q[3]});
}

bool MavlinkDeviceState::apply(const mavlink::Message& message, double now_s) {
    if (const auto* a = std::get_if<mavlink::GimbalDeviceAttitudeStatus>(&message.payload)) {
        device_system_ = message.sysid;
        device_component_ = message.compid;
        on_attitude(*a, now_s);
        return true;
    }
    if (const auto* i = std::get_if<mavlink::GimbalDeviceInformation>(&message.payload)) {
        device_system_ = message.sysid;
        device_component_ = message.compid;
        on_information(*i, now_s);
        return true;
    }
    return false;
}

void MavlinkDeviceState::on_attitude(const mavlink::GimbalDeviceAttitudeStatus& m, double now_s) {
    const auto e = euler_of(m.q);
    DeviceAttitude a = data_.attitude.value_or(DeviceAttitude{});
    // A NaN quaternion keeps the last angles (the device says it has none now) but counts as
    // a report: its failure flags and rates are current.
    if (e) {
        a.roll_deg = e->roll_deg;
        a.pitch_deg = e->pitch_deg;
        a.yaw_deg = e->yaw_deg;
    }
    a.earth_frame = yaw_in_earth_frame(m.flags);
    a.angular_velocity_dps = {radians_per_second(m.angular_velocity_x),
                              radians_per_second(m.angular_velocity_y),
                              radians_per_second(m.angular_velocity_z)};
    a.failure_flags = m.failure_flags;
    a.time_boot_ms = m.time_boot_ms;
    a.received_s = now_s;
    data_.attitude = a;
    ++attitudes_;
    lost_reported_ = false;
    data_.telemetry = derive_telemetry();
}

void MavlinkDeviceState::on_information(const mavlink::GimbalDeviceInformation& m, double) {
    data_.information = m;
}

void MavlinkDeviceState::set_vehicle(const std::optional<vehicle::AircraftFix>& fix) {
    vehicle_ = fix;
    if (options_.geoid_undulation_m)
        geoid_undulation_m_ = *options_.geoid_undulation_m;
    else if (fix && options_.geoid)
        geoid_undulation_m_ = options_.geoid(fix->lat_deg, fix->lon_deg).value_or(0.0);
}

std::optional<geo::Lla> MavlinkDeviceState::camera() const {
    if (!vehicle_) return std::nullopt;
    return geo::Lla{vehicle_->lat_deg, vehicle_->lon_deg,
                    geo::ellipsoid_from_msl(vehicle_->alt_msl_m, geoid_undulation_m_)};
}

bool MavlinkDeviceState::earth_frame_supported() const {
    constexpr std::uint16_t supports_yaw_in_earth_frame = 4096;
    return data_.information && (data_.information->cap_flags & supports_yaw_in_earth_frame) != 0;
}

std::optional<double> MavlinkDeviceState::pan_deg() const {
    if (!data_.attitude) return std::nullopt;
    if (!data_.attitude->earth_frame) return session::wrap180(data_.attitude->yaw_deg);
    if (!vehicle_) return std::nullopt;
    return session::wrap180(data_.attitude->yaw_deg - vehicle_->yaw_deg);
}

std::optional<geo::Quat> MavlinkDeviceState::line_of_sight() const {
    if (!data_.attitude) return std::nullopt;
    double yaw = data_.attitude->yaw_deg;
    if (!data_.attitude->earth_frame) {
        if (!vehicle_) return std::nullopt;
        yaw += vehicle_->yaw_deg;
    }
    return geo::normalized(geo::euler_to_quat(
        geo::EulerDeg{data_.attitude->roll_deg, data_.attitude->pitch_deg, session::wrap180(yaw)}));
}

state::Telemetry MavlinkDeviceState::derive_telemetry() const {
    state::Telemetry t;
    if (const auto pan = pan_deg()) t.pan = angle_deg(*pan);
    t.tilt = angle_deg(data_.attitude->pitch_deg);
    t.hfov = angle_deg(options_.hfov_deg);
    t.vfov = angle_deg(options_.vfov_deg);
    const auto los = line_of_sight();
    if (!vehicle_ || !los) return t;
    // The device reports no target of its own: where its line of sight meets the ground.
    const geo::CameraPose pose{*camera(), *los, options_.hfov_deg, options_.vfov_deg};
    session::fill_from_aircraft(t, *vehicle_, geoid_undulation_m_, pose,
                                geo::Ground{options_.terrain, options_.ground_alt_m});
    return t;
}

void MavlinkDeviceState::write_device(state::JsonWriter& d, double now_s) const {
    if (data_.information) {
        const auto& i = *data_.information;
        d.string("vendor", device_text(i.vendor_name));
        d.string("model", device_text(i.model_name));
        d.string("firmware", firmware_text(i.firmware_version));
        d.array("cap_flags", cap_flag_names(i.cap_flags));
        d.object("limits", [&](state::JsonWriter& l) {
            for (const auto& [axis, min, max] : {std::tuple{"roll", i.roll_min, i.roll_max},
                                                 std::tuple{"pitch", i.pitch_min, i.pitch_max},
                                                 std::tuple{"yaw", i.yaw_min, i.yaw_max}}) {
                const auto [lo, hi] = device_limits(min, max);
                l.angle(std::string(axis) + "_min", lo);
                l.angle(std::string(axis) + "_max", hi);
            }
        });
    } else {
        for (const char* key : {"vendor", "model", "firmware", "cap_flags", "limits"}) d.null(key);
    }
    if (data_.attitude) {
        const auto& a = *data_.attitude;
        d.object("attitude", [&](state::JsonWriter& at) {
            at.angle("roll", a.roll_deg);
            at.angle("pitch", a.pitch_deg);
            at.angle("yaw", a.yaw_deg);
            at.string("frame", a.earth_frame ? "earth" : "vehicle");
        });
        d.array("angular_velocity", a.angular_velocity_dps, state::angle_json);
        d.array("failure_flags", failure_flag_names(a.failure_flags));
        d.seconds("age_s", std::max(0.0, now_s - a.received_s));
    } else {
        for (const char* key : {"attitude", "angular_velocity", "failure_flags", "age_s"})
            d.null(key);
    }
}

bool MavlinkDeviceState::stale(double now_s) const {
    return !data_.attitude || now_s - data_.attitude->received_s > options_.stale_after_s;
}

void MavlinkDeviceState::tick(double now_s, std::vector<state::Event>& events) {
    if (data_.attitude && !lost_reported_ && stale(now_s)) {
        lost_reported_ = true;
        events.push_back(
            state::Event{"lost", {{"age_s", state::seconds(now_s - data_.attitude->received_s)}}});
    }
}

void MavlinkDeviceState::write(state::JsonWriter& w, double now_s) const {
    w.object("device", [&](state::JsonWriter& d) { write_device(d, now_s); });
    w.object("telemetry", data_.telemetry);
    w.json("stare", stare_);
}

json MavlinkDeviceState::snapshot(double now_s) const {
    json out = json::object();
    state::JsonWriter w(out);
    write(w, now_s);
    return out;
}

}  // namespace gimbal::protocols
