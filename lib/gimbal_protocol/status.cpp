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

bool healthy(const session::GimbalView& state) {
    return state.connected && !state.stale;
}

// Pan and tilt limits in radians, NaN where the gimbal reports none - or reports a pair no
// gimbal has (outside -360..360 degrees, or min above max): unknown, not relayed (section 14).
struct Limits {
    float pan_min = mav::nan_f, pan_max = mav::nan_f, tilt_min = mav::nan_f, tilt_max = mav::nan_f;
};
Limits limits_of(const session::GimbalView& state) {
    const auto* caps = state.capabilities;
    if (!caps) return {};
    const session::Limits l = caps->limits();
    const auto rad = [](std::optional<double> deg) {
        return deg && std::isfinite(*deg) && std::abs(*deg) <= 360.0
                   ? static_cast<float>(*deg * deg_to_rad)
                   : mav::nan_f;
    };
    Limits out{rad(l.pan_min_deg), rad(l.pan_max_deg), rad(l.tilt_min_deg), rad(l.tilt_max_deg)};
    if (out.pan_min > out.pan_max) out.pan_min = out.pan_max = mav::nan_f;
    if (out.tilt_min > out.tilt_max) out.tilt_min = out.tilt_max = mav::nan_f;
    return out;
}

// GIMBAL_MANAGER_CAP_FLAGS from what the gimbal can do.
std::uint32_t capabilities(const ExposedGimbal& g) {
    namespace c = mav::gimbal_cap;
    std::uint32_t caps = c::has_pitch_axis | c::has_yaw_axis | c::has_yaw_follow;
    const auto features = g.features();
    if (!features) return caps;
    const session::Features& f = *features;
    if (f.pitch_lock) caps |= c::has_pitch_lock;
    if (f.yaw_lock) caps |= c::has_yaw_lock;
    if (f.yaw_in_earth_frame) caps |= c::supports_yaw_in_earth_frame;
    if (f.infinite_yaw) caps |= c::supports_infinite_yaw;
    if (f.geopoint) caps |= c::can_point_location_global;
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

std::optional<geo::Quat> line_of_sight(const session::GimbalView& state) {
    return state.capabilities ? state.capabilities->line_of_sight() : std::nullopt;
}

mav::GimbalDeviceAttitudeStatus attitude_status(const ExposedGimbal& g,
                                                const session::GimbalView& state,
                                                std::uint32_t time_boot_ms) {
    mav::GimbalDeviceAttitudeStatus s;
    s.time_boot_ms = time_boot_ms;
    s.gimbal_device_id = g.device_id;
    namespace fl = mav::gimbal_flags;
    s.flags = static_cast<std::uint16_t>(fl::roll_lock | fl::pitch_lock | fl::yaw_in_earth_frame);
    if (const auto q = line_of_sight(state))
        s.q = {static_cast<float>(q->w), static_cast<float>(q->x), static_cast<float>(q->y),
               static_cast<float>(q->z)};
    else
        s.q = {mav::nan_f, mav::nan_f, mav::nan_f, mav::nan_f};
    if (!healthy(state)) s.failure_flags |= mav::gimbal_error::comms_error;
    return s;
}

mav::CameraFovStatus fov_status(const ExposedGimbal& g, const session::GimbalView& state,
                                std::uint32_t time_boot_ms) {
    mav::CameraFovStatus s;
    s.time_boot_ms = time_boot_ms;
    s.camera_device_id = g.device_id;
    const auto* caps = state.capabilities;
    const session::View v = caps ? caps->view() : session::View{};
    s.lat_camera = degE7(v.lat_deg);
    s.lon_camera = degE7(v.lon_deg);
    s.alt_camera = mm(v.alt_msl_m);
    s.lat_image = degE7(v.target_lat_deg);
    s.lon_image = degE7(v.target_lon_deg);
    s.alt_image = mm(v.target_alt_msl_m);  // CAMERA_FOV_STATUS wants MSL
    s.hfov = f(v.hfov_deg);
    s.vfov = f(v.vfov_deg);
    if (const auto q = line_of_sight(state))
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
                                                  const session::GimbalView& state,
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
    // Limits not known: the whole circle in yaw, straight down to straight up in pitch.
    const float pi = std::numbers::pi_v<float>;
    if (std::isnan(l.pan_min) || std::isnan(l.pan_max)) {
        m.yaw_min = -pi;
        m.yaw_max = pi;
    }
    if (std::isnan(l.tilt_min)) m.pitch_min = -pi / 2;
    if (std::isnan(l.tilt_max)) m.pitch_max = pi / 2;
    return m;
}

// Vendor and model as MAVLink announces them: what the gimbal says of itself.
namespace {
session::Identity identity_of(const ExposedGimbal& g, const session::GimbalView& state) {
    const auto* caps = state.capabilities;
    return caps ? caps->identity() : session::Identity{g.protocol, g.protocol, std::nullopt};
}
}  // namespace

mav::GimbalDeviceInformation device_information(const ExposedGimbal& g,
                                                const session::GimbalView& state,
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
    const session::Identity id = identity_of(g, state);
    mav::set_text(d.vendor_name, id.vendor);
    mav::set_text(d.model_name, id.model);
    mav::set_text(d.custom_name, g.name);
    return d;
}

mav::CameraInformation camera_information(const ExposedGimbal& g, const session::GimbalView& state,
                                          std::uint32_t time_boot_ms) {
    mav::CameraInformation c;
    c.time_boot_ms = time_boot_ms;
    c.gimbal_device_id = g.device_id;
    c.camera_device_id = g.device_id;
    const session::Identity id = identity_of(g, state);
    mav::set_text(c.vendor_name, id.vendor);
    mav::set_text(c.model_name, id.model);
    c.focal_length = mav::nan_f;
    c.sensor_size_h = mav::nan_f;
    c.sensor_size_v = mav::nan_f;
    const auto* caps = state.capabilities;
    if (!caps) return c;
    const session::Camera cam = caps->camera();
    if (cam.basic_zoom) c.flags = mav::camera_cap_has_basic_zoom;
    c.focal_length = f(cam.focal_length_mm);
    if (cam.width_px && cam.height_px) {
        c.resolution_h = static_cast<std::uint16_t>(*cam.width_px);
        c.resolution_v = static_cast<std::uint16_t>(*cam.height_px);
    }
    c.sensor_size_h = f(cam.sensor_width_mm);
    c.sensor_size_v = f(cam.sensor_height_mm);
    return c;
}

}  // namespace gimbal::gimbal_protocol
