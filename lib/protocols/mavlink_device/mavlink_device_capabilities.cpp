#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"

#include <cmath>

#include "geo/wgs84.hpp"
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
    // The device's angles read in place: copying a disengaged optional<double> makes GCC 12
    // at -O2 warn (-Wmaybe-uninitialized) about its unset value.
    const auto* tel = data_.telemetry ? &*data_.telemetry : nullptr;
    const bool have_pan = tel && tel->pan, have_tilt = tel && tel->tilt;
    double pan = 0;
    if (t.yaw_deg && t.yaw_frame == session::YawFrame::earth) {
        if (!t.vehicle_heading_deg)
            return session::unavailable("yaw from north needs the aircraft's heading");
        pan = session::wrap180(*t.yaw_deg - *t.vehicle_heading_deg);
    } else if (t.yaw_deg) {
        pan = *t.yaw_deg;
    } else if (have_pan) {
        pan = *tel->pan;
    } else {
        return session::unavailable("no attitude from the device yet for the angle left out");
    }
    // Not value_or(*tel->tilt): that would read an empty optional when a pitch is given.
    double tilt = 0;
    if (t.pitch_deg)
        tilt = *t.pitch_deg;
    else if (have_tilt)
        tilt = *tel->tilt;
    else
        return session::unavailable("no attitude from the device yet for the angle left out");
    return json{{"cmd", "position"}, {"pan", pan}, {"tilt", tilt}};
}

session::Request MavlinkDeviceCapabilities::rate(const session::RateTarget& t) const {
    return json{{"cmd", "rate"},
                {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

session::Request MavlinkDeviceCapabilities::geopoint(const session::GeoTarget& t) const {
    return json{{"cmd", "geopoint"},
                {"lat", t.lat_deg},
                {"lon", t.lon_deg},
                {"alt", t.alt_msl_m},
                {"alt_ref", "msl"}};
}

session::Request MavlinkDeviceCapabilities::stop() const {
    return json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}};
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
    session::View v;
    if (!data_.telemetry) return v;
    const state::Telemetry& t = *data_.telemetry;
    v.lat_deg = t.lat;
    v.lon_deg = t.lon;
    v.alt_msl_m = t.alt_msl;
    v.alt_m = t.alt;
    if (t.target) {
        v.target_lat_deg = t.target->lat;
        v.target_lon_deg = t.target->lon;
        if (t.geoid_undulation)
            v.target_alt_msl_m = geo::msl_from_ellipsoid(t.target->alt, *t.geoid_undulation);
    }
    v.hfov_deg = t.hfov;
    v.vfov_deg = t.vfov;
    return v;
}

command::Result<session::ImageView> MavlinkDeviceCapabilities::image() const {
    const auto* t = data_.telemetry ? &*data_.telemetry : nullptr;
    const auto los = line_of_sight();
    if (!t || !t->lat || !t->lon || !t->alt || !t->hfov || !t->vfov || !los)
        return command::Error{command::code::unavailable,
                              "no device attitude with a vehicle position yet"};
    session::ImageView v;
    v.camera = geo::CameraPose{{*t->lat, *t->lon, *t->alt}, *los, *t->hfov, *t->vfov};
    if (t->target) v.flat_alt_m = t->target->alt;
    v.geoid_undulation_m = t->geoid_undulation;
    return v;
}

std::optional<geo::Quat> MavlinkDeviceCapabilities::platform_attitude() const {
    const auto* t = data_.telemetry ? &*data_.telemetry : nullptr;
    if (!t || !t->roll || !t->pitch || !t->yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*t->roll, *t->pitch, *t->yaw});
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
