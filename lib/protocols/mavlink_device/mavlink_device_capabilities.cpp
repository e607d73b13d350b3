#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"

#include <cmath>

#include "geo/wgs84.hpp"
#include "session/aimed_telemetry.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using state::angle_deg;

namespace {

// A text of the information, when the device sent one.
std::optional<std::string> text(std::string t) {
    return t.empty() ? std::nullopt : std::optional(std::move(t));
}

}  // namespace

session::Features mavlink_device_features() {
    session::Features f;
    f.point_angles = f.rate = f.geopoint = true;
    f.pitch_lock = f.yaw_lock = f.yaw_in_earth_frame = true;
    f.absolute_angles = true;
    return f;
}

session::Request MavlinkDeviceCapabilities::point_angles(const session::AnglesTarget& t) const {
    return session::nose_angles_request(t, data_.telemetry ? &*data_.telemetry : nullptr, "device");
}

session::Request MavlinkDeviceCapabilities::rate(const session::RateTarget& t) const {
    return session::nose_rate_request(t);
}

session::Request MavlinkDeviceCapabilities::geopoint(const session::GeoTarget& t) const {
    return session::msl_geopoint_request(t);
}

session::Request MavlinkDeviceCapabilities::stop() const {
    return session::stop_rates_request();
}

session::Request MavlinkDeviceCapabilities::zoom(const session::ZoomTarget&) const {
    return session::unsupported(
        "a MAVLink gimbal device has no zoom (the camera is another "
        "component)");
}

std::optional<geo::Quat> MavlinkDeviceCapabilities::line_of_sight() const {
    if (!data_.attitude) return std::nullopt;
    const DeviceAttitude& a = *data_.attitude;
    // The attitude as STATE `device.attitude` shows it.
    double yaw = angle_deg(a.yaw_deg);
    if (!a.earth_frame) {
        const auto heading = data_.telemetry ? data_.telemetry->yaw : std::nullopt;
        if (!heading) return std::nullopt;
        yaw += *heading;
    }
    return geo::normalized(geo::euler_to_quat(
        geo::EulerDeg{angle_deg(a.roll_deg), angle_deg(a.pitch_deg), session::wrap180(yaw)}));
}

session::View MavlinkDeviceCapabilities::view() const {
    session::View v = session::view_from(data_.telemetry ? &*data_.telemetry : nullptr);
    return v;
}

command::Result<session::ImageView> MavlinkDeviceCapabilities::image() const {
    return session::image_from(data_.telemetry ? &*data_.telemetry : nullptr, line_of_sight(),
                               "device");
}

std::optional<geo::Quat> MavlinkDeviceCapabilities::platform_attitude() const {
    return session::aircraft_attitude_from(data_.telemetry ? &*data_.telemetry : nullptr);
}

session::Identity MavlinkDeviceCapabilities::identity() const {
    if (!data_.information) return {"MAVLink", "gimbal device", std::nullopt};
    const auto& i = *data_.information;
    return {text(device_text(i.vendor_name)).value_or("MAVLink"),
            text(device_text(i.model_name)).value_or("gimbal device"),
            text(firmware_text(i.firmware_version))};
}

session::Limits MavlinkDeviceCapabilities::limits() const {
    if (!data_.information) return {};
    const auto& i = *data_.information;
    const auto deg = [](std::optional<double> d) -> std::optional<double> {
        if (!d) return std::nullopt;
        return angle_deg(*d);
    };
    const auto [yaw_min, yaw_max] = device_limits(i.yaw_min, i.yaw_max);
    const auto [pitch_min, pitch_max] = device_limits(i.pitch_min, i.pitch_max);
    session::Limits l;
    l.pan_min_deg = deg(yaw_min);
    l.pan_max_deg = deg(yaw_max);
    l.tilt_min_deg = deg(pitch_min);
    l.tilt_max_deg = deg(pitch_max);
    return l;
}

session::Camera MavlinkDeviceCapabilities::camera() const {
    return {};
}

}  // namespace gimbal::protocols
