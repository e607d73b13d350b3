#include "gimbal_protocol/status.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>
#include <utility>

#include "session/capabilities.hpp"

namespace gimbal::gimbal_protocol {

namespace mav = gimbal::mavlink;

namespace {

constexpr double deg_to_rad = std::numbers::pi / 180.0;

std::int32_t degE7(std::optional<double> deg) {
    if (!deg || std::abs(*deg) > 180) return mav::CameraFovStatus::unknown;
    return static_cast<std::int32_t>(std::lround(*deg * 1e7));
}

std::int32_t mm(std::optional<double> m) {
    if (!m || std::abs(*m) > 2e6) return mav::CameraFovStatus::unknown;
    return static_cast<std::int32_t>(std::lround(*m * 1000));
}

float f(std::optional<double> v) {
    return v ? static_cast<float>(*v) : mav::nan_f;
}

bool healthy(const nlohmann::json& state) {
    const auto* link = state.is_object() && state.contains("link") ? &state["link"] : nullptr;
    const bool connected = link && link->is_object() && link->value("connected", false);
    const bool stale = !state.is_object() || state.value("stale", true);
    return connected && !stale;
}

// Pan and tilt limits in radians from the Orion LIMITS packet (degrees in STATE).
struct Limits {
    float pan_min = mav::nan_f, pan_max = mav::nan_f, tilt_min = mav::nan_f, tilt_max = mav::nan_f;
};
Limits limits_of(const nlohmann::json& state) {
    Limits l;
    const auto* lim = state.is_object() && state.contains("limits") ? &state["limits"] : nullptr;
    if (!lim || !lim->is_object()) return l;
    const auto axis = [&](const char* key, std::size_t i) -> float {
        const auto it = lim->find(key);
        if (it == lim->end() || !it->is_array() || it->size() <= i || !(*it)[i].is_number())
            return mav::nan_f;
        return static_cast<float>((*it)[i].get<double>() * deg_to_rad);
    };
    l.pan_min = axis("min_pos", 0);
    l.pan_max = axis("max_pos", 0);
    l.tilt_min = axis("min_pos", 1);
    l.tilt_max = axis("max_pos", 1);
    return l;
}

std::uint32_t capabilities(const ExposedGimbal& g) {
    namespace c = mav::gimbal_cap;
    std::uint32_t caps = c::has_pitch_axis | c::has_yaw_axis | c::has_yaw_follow;
    if (g.protocol == "orion")
        caps |= c::has_pitch_lock | c::has_yaw_lock | c::supports_yaw_in_earth_frame |
                c::supports_infinite_yaw | c::can_point_location_global;
    return caps;
}

}  // namespace

mav::Heartbeat heartbeat() {
    mav::Heartbeat hb;
    hb.type = mav::mav_type_gimbal;
    hb.autopilot = mav::mav_autopilot_invalid;
    hb.system_status = static_cast<std::uint8_t>(mav::MavState::active);
    hb.mavlink_version = 3;
    return hb;
}

std::optional<geo::Quat> line_of_sight(const nlohmann::json& state, const std::string& protocol) {
    if (protocol == "orion") {
        const auto* t =
            state.is_object() && state.contains("telemetry") ? &state["telemetry"] : nullptr;
        if (!t || !t->is_object()) return std::nullopt;
        const auto pan = session::number_at(*t, {"pan"});
        const auto tilt = session::number_at(*t, {"tilt"});
        const auto it = t->find("quat");
        if (!pan || !tilt || it == t->end() || !it->is_array() || it->size() != 4)
            return std::nullopt;
        geo::Quat mount;
        double* parts[] = {&mount.w, &mount.x, &mount.y, &mount.z};
        for (std::size_t i = 0; i < 4; ++i) {
            if (!(*it)[i].is_number()) return std::nullopt;
            *parts[i] = (*it)[i].get<double>();
            if (!std::isfinite(*parts[i])) return std::nullopt;
        }
        return geo::normalized(geo::normalized(mount) *
                               geo::euler_to_quat(geo::EulerDeg{0, *tilt, *pan}));
    }
    const auto ur = session::number_at(state, {"output", "uav", "roll"});
    const auto up = session::number_at(state, {"output", "uav", "pitch"});
    const auto uy = session::number_at(state, {"output", "uav", "yaw"});
    const auto gr = session::number_at(state, {"output", "gimbal", "roll"});
    const auto gp = session::number_at(state, {"output", "gimbal", "pitch"});
    const auto gy = session::number_at(state, {"output", "gimbal", "yaw"});
    if (!ur || !up || !uy || !gp || !gy) return std::nullopt;
    return geo::normalized(geo::euler_to_quat(geo::EulerDeg{*ur, *up, *uy}) *
                           geo::euler_to_quat(geo::EulerDeg{gr.value_or(0), *gp, *gy}));
}

mav::GimbalDeviceAttitudeStatus attitude_status(const ExposedGimbal& g, const nlohmann::json& state,
                                                std::uint32_t time_boot_ms) {
    mav::GimbalDeviceAttitudeStatus s;
    s.time_boot_ms = time_boot_ms;
    s.gimbal_device_id = g.device_id;
    namespace fl = mav::gimbal_flags;
    s.flags = static_cast<std::uint16_t>(fl::roll_lock | fl::pitch_lock | fl::yaw_in_earth_frame);
    if (const auto q = line_of_sight(state, g.protocol))
        s.q = {static_cast<float>(q->w), static_cast<float>(q->x), static_cast<float>(q->y),
               static_cast<float>(q->z)};
    else
        s.q = {mav::nan_f, mav::nan_f, mav::nan_f, mav::nan_f};
    if (!healthy(state)) s.failure_flags |= mav::gimbal_error::comms_error;
    return s;
}

mav::CameraFovStatus fov_status(const ExposedGimbal& g, const nlohmann::json& state,
                                std::uint32_t time_boot_ms) {
    mav::CameraFovStatus s;
    s.time_boot_ms = time_boot_ms;
    s.camera_device_id = g.device_id;
    if (g.protocol == "orion") {
        s.lat_camera = degE7(session::number_at(state, {"telemetry", "lat"}));
        s.lon_camera = degE7(session::number_at(state, {"telemetry", "lon"}));
        s.alt_camera = mm(session::number_at(state, {"telemetry", "alt_msl"}));
        s.lat_image = degE7(session::number_at(state, {"telemetry", "target", "lat"}));
        s.lon_image = degE7(session::number_at(state, {"telemetry", "target", "lon"}));
        // The target's altitude is WGS84; CAMERA_FOV_STATUS wants MSL.
        const auto alt = session::number_at(state, {"telemetry", "target", "alt"});
        const auto n = session::number_at(state, {"telemetry", "geoid_undulation"});
        s.alt_image = mm(alt && n ? std::optional<double>{*alt - *n} : std::nullopt);
        s.hfov = f(session::number_at(state, {"telemetry", "hfov"}));
        s.vfov = f(session::number_at(state, {"telemetry", "vfov"}));
    } else {
        s.lat_camera = degE7(session::number_at(state, {"output", "uav", "lat"}));
        s.lon_camera = degE7(session::number_at(state, {"output", "uav", "lon"}));
        s.alt_camera = mm(session::number_at(state, {"output", "uav", "alt_msl"}));
        s.lat_image = degE7(session::number_at(state, {"output", "target", "lat"}));
        s.lon_image = degE7(session::number_at(state, {"output", "target", "lon"}));
        s.alt_image = mm(session::number_at(state, {"output", "target", "alt_msl"}));
    }
    if (const auto q = line_of_sight(state, g.protocol))
        s.q = {static_cast<float>(q->w), static_cast<float>(q->x), static_cast<float>(q->y),
               static_cast<float>(q->z)};
    return s;
}

mav::GimbalManagerStatus manager_status(const ExposedGimbal& g, const Control& control,
                                        std::uint32_t time_boot_ms) {
    mav::GimbalManagerStatus s;
    s.time_boot_ms = time_boot_ms;
    s.gimbal_device_id = g.device_id;
    s.flags = mav::gimbal_flags::roll_lock | mav::gimbal_flags::pitch_lock;
    if (control.primary()) {
        s.primary_control_sysid = control.primary()->sysid;
        s.primary_control_compid = control.primary()->compid;
    }
    if (control.secondary()) {
        s.secondary_control_sysid = control.secondary()->sysid;
        s.secondary_control_compid = control.secondary()->compid;
    }
    return s;
}

mav::GimbalManagerInformation manager_information(const ExposedGimbal& g,
                                                  const nlohmann::json& state,
                                                  std::uint32_t time_boot_ms) {
    mav::GimbalManagerInformation m;
    m.time_boot_ms = time_boot_ms;
    m.gimbal_device_id = g.device_id;
    m.cap_flags = capabilities(g);
    const Limits l = limits_of(state);
    m.roll_min = 0;
    m.roll_max = 0;
    m.pitch_min = l.tilt_min;
    m.pitch_max = l.tilt_max;
    m.yaw_min = l.pan_min;
    m.yaw_max = l.pan_max;
    if (g.protocol == "viewpro" || std::isnan(l.pan_min)) {
        // No LIMITS packet: the whole circle in yaw, straight down to straight up in pitch.
        const float pi = std::numbers::pi_v<float>;
        m.pitch_min = std::isnan(l.tilt_min) ? -pi / 2 : l.tilt_min;
        m.pitch_max = std::isnan(l.tilt_max) ? pi / 2 : l.tilt_max;
        m.yaw_min = -pi;
        m.yaw_max = pi;
    }
    return m;
}

// Vendor and model as MAVLink announces them: what the gimbal reports of itself (a MAVLink
// gimbal device's STATE `device`), else the protocol's maker.
namespace {
std::pair<std::string, std::string> maker_of(const ExposedGimbal& g, const nlohmann::json& state) {
    const auto* vendor = session::state_at(state, {"device", "vendor"});
    const auto* model = session::state_at(state, {"device", "model"});
    if (vendor && vendor->is_string() && model && model->is_string())
        return {vendor->get<std::string>(), model->get<std::string>()};
    if (g.protocol == "orion") return {"Trillium", "Orion"};
    if (g.protocol == "viewpro") return {"Viewpro", "Viewpro"};
    return {"MAVLink", "gimbal device"};
}
}  // namespace

mav::GimbalDeviceInformation device_information(const ExposedGimbal& g, const nlohmann::json& state,
                                                std::uint32_t time_boot_ms) {
    mav::GimbalDeviceInformation d;
    d.uid = g.device_id;
    d.time_boot_ms = time_boot_ms;
    d.gimbal_device_id = g.device_id;
    d.cap_flags = static_cast<std::uint16_t>(capabilities(g) & 0xFFFF);
    d.cap_flags2 = capabilities(g);
    const Limits l = limits_of(state);
    d.roll_min = 0;
    d.roll_max = 0;
    d.pitch_min = l.tilt_min;
    d.pitch_max = l.tilt_max;
    d.yaw_min = l.pan_min;
    d.yaw_max = l.pan_max;
    const auto [vendor, model] = maker_of(g, state);
    mav::set_text(d.vendor_name, vendor);
    mav::set_text(d.model_name, model);
    mav::set_text(d.custom_name, g.name);
    return d;
}

mav::CameraInformation camera_information(const ExposedGimbal& g, const nlohmann::json& state,
                                          std::uint32_t time_boot_ms) {
    mav::CameraInformation c;
    c.time_boot_ms = time_boot_ms;
    c.gimbal_device_id = g.device_id;
    c.camera_device_id = g.device_id;
    const auto [vendor, model] = maker_of(g, state);
    mav::set_text(c.vendor_name, vendor);
    mav::set_text(c.model_name, model);
    c.focal_length = mav::nan_f;
    c.sensor_size_h = mav::nan_f;
    c.sensor_size_v = mav::nan_f;
    if (g.protocol == "orion") {
        c.flags = mav::camera_cap_has_basic_zoom;
        const auto* cams =
            state.is_object() && state.contains("cameras") ? &state["cameras"] : nullptr;
        if (cams && cams->is_object() && cams->contains("cameras") &&
            (*cams)["cameras"].is_array() && !(*cams)["cameras"].empty()) {
            const auto& cam = (*cams)["cameras"][0];
            c.focal_length = f(session::number_at(cam, {"min_focal_length_mm"}));
            const auto w = session::number_at(cam, {"array_width"});
            const auto h = session::number_at(cam, {"array_height"});
            const auto pitch = session::number_at(cam, {"pixel_pitch_mm"});
            if (w && h) {
                c.resolution_h = static_cast<std::uint16_t>(*w);
                c.resolution_v = static_cast<std::uint16_t>(*h);
                if (pitch) {
                    c.sensor_size_h = static_cast<float>(*w * *pitch);
                    c.sensor_size_v = static_cast<float>(*h * *pitch);
                }
            }
        }
    }
    return c;
}

}  // namespace gimbal::gimbal_protocol
