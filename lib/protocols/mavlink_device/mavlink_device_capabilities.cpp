#include "protocols/mavlink_device/mavlink_device_capabilities.hpp"

#include <cmath>

#include "geo/wgs84.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using session::number_at;
using session::state_at;

namespace {

std::optional<std::string> text_at(const json& state, std::initializer_list<const char*> keys) {
    const json* v = state_at(state, keys);
    if (!v || !v->is_string() || v->get_ref<const std::string&>().empty()) return std::nullopt;
    return v->get<std::string>();
}

}  // namespace

session::Features MavlinkDeviceCapabilities::features() const {
    session::Features f;
    f.point_angles = f.rate = f.geopoint = true;
    f.pitch_lock = f.yaw_lock = f.yaw_in_earth_frame = true;
    f.absolute_angles = true;
    return f;
}

session::Request MavlinkDeviceCapabilities::point_angles(const json& state,
                                                         const session::AnglesTarget& t) const {
    const auto cur_pan = number_at(state, {"telemetry", "pan"});
    const auto cur_tilt = number_at(state, {"telemetry", "tilt"});
    double pan = 0;
    if (t.yaw_deg && t.yaw_frame == session::YawFrame::earth) {
        if (!t.vehicle_heading_deg)
            return session::unavailable("yaw from north needs the aircraft's heading");
        pan = session::wrap180(*t.yaw_deg - *t.vehicle_heading_deg);
    } else if (t.yaw_deg) {
        pan = *t.yaw_deg;
    } else if (cur_pan) {
        pan = *cur_pan;
    } else {
        return session::unavailable("no attitude from the device yet for the angle left out");
    }
    if (!t.pitch_deg && !cur_tilt)
        return session::unavailable("no attitude from the device yet for the angle left out");
    // Not value_or(*cur_tilt): that would read an empty optional when the pitch is given.
    const double tilt = t.pitch_deg ? *t.pitch_deg : *cur_tilt;
    return json{{"cmd", "position"}, {"pan", pan}, {"tilt", tilt}};
}

session::Request MavlinkDeviceCapabilities::rate(const json&, const session::RateTarget& t) const {
    return json{{"cmd", "rate"},
                {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

session::Request MavlinkDeviceCapabilities::geopoint(const json&,
                                                     const session::GeoTarget& t) const {
    return json{{"cmd", "geopoint"},
                {"lat", t.lat_deg},
                {"lon", t.lon_deg},
                {"alt", t.alt_msl_m},
                {"alt_ref", "msl"}};
}

session::Request MavlinkDeviceCapabilities::stop(const json&) const {
    return json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}};
}

session::Request MavlinkDeviceCapabilities::zoom(const json&, const session::ZoomTarget&) const {
    return session::unsupported(
        "a MAVLink gimbal device has no zoom (the camera is another "
        "component)");
}

std::optional<geo::Quat> MavlinkDeviceCapabilities::line_of_sight(const json& state) const {
    const auto roll = number_at(state, {"device", "attitude", "roll"});
    const auto pitch = number_at(state, {"device", "attitude", "pitch"});
    auto yaw = number_at(state, {"device", "attitude", "yaw"});
    const json* frame = state_at(state, {"device", "attitude", "frame"});
    if (!roll || !pitch || !yaw || !frame || !frame->is_string()) return std::nullopt;
    if (*frame != "earth") {
        const auto heading = number_at(state, {"telemetry", "yaw"});
        if (!heading) return std::nullopt;
        *yaw += *heading;
    }
    return geo::normalized(
        geo::euler_to_quat(geo::EulerDeg{*roll, *pitch, session::wrap180(*yaw)}));
}

session::View MavlinkDeviceCapabilities::view(const json& state) const {
    session::View v;
    v.lat_deg = number_at(state, {"telemetry", "lat"});
    v.lon_deg = number_at(state, {"telemetry", "lon"});
    v.alt_msl_m = number_at(state, {"telemetry", "alt_msl"});
    v.alt_m = number_at(state, {"telemetry", "alt"});
    v.target_lat_deg = number_at(state, {"telemetry", "target", "lat"});
    v.target_lon_deg = number_at(state, {"telemetry", "target", "lon"});
    const auto talt = number_at(state, {"telemetry", "target", "alt"});
    const auto n = number_at(state, {"telemetry", "geoid_undulation"});
    if (talt && n) v.target_alt_msl_m = geo::msl_from_ellipsoid(*talt, *n);
    v.hfov_deg = number_at(state, {"telemetry", "hfov"});
    v.vfov_deg = number_at(state, {"telemetry", "vfov"});
    return v;
}

command::Result<session::ImageView> MavlinkDeviceCapabilities::image(const json& state) const {
    const auto lat = number_at(state, {"telemetry", "lat"});
    const auto lon = number_at(state, {"telemetry", "lon"});
    const auto alt = number_at(state, {"telemetry", "alt"});
    const auto hfov = number_at(state, {"telemetry", "hfov"});
    const auto vfov = number_at(state, {"telemetry", "vfov"});
    const auto los = line_of_sight(state);
    if (!lat || !lon || !alt || !hfov || !vfov || !los)
        return command::Error{command::code::unavailable,
                              "no device attitude with a vehicle position yet"};
    session::ImageView v;
    v.camera = geo::CameraPose{{*lat, *lon, *alt}, *los, *hfov, *vfov};
    v.flat_alt_m = number_at(state, {"telemetry", "target", "alt"});
    v.geoid_undulation_m = number_at(state, {"telemetry", "geoid_undulation"});
    return v;
}

std::optional<geo::Quat> MavlinkDeviceCapabilities::platform_attitude(const json& state) const {
    const auto roll = number_at(state, {"telemetry", "roll"});
    const auto pitch = number_at(state, {"telemetry", "pitch"});
    const auto yaw = number_at(state, {"telemetry", "yaw"});
    if (!roll || !pitch || !yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*roll, *pitch, *yaw});
}

session::Identity MavlinkDeviceCapabilities::identity(const json& state) const {
    return {text_at(state, {"device", "vendor"}).value_or("MAVLink"),
            text_at(state, {"device", "model"}).value_or("gimbal device"),
            text_at(state, {"device", "firmware"})};
}

session::Limits MavlinkDeviceCapabilities::limits(const json& state) const {
    session::Limits l;
    l.pan_min_deg = number_at(state, {"device", "limits", "yaw_min"});
    l.pan_max_deg = number_at(state, {"device", "limits", "yaw_max"});
    l.tilt_min_deg = number_at(state, {"device", "limits", "pitch_min"});
    l.tilt_max_deg = number_at(state, {"device", "limits", "pitch_max"});
    return l;
}

session::Camera MavlinkDeviceCapabilities::camera(const json&) const {
    return {};
}

const MavlinkDeviceCapabilities& mavlink_device_capabilities() {
    static const MavlinkDeviceCapabilities instance;
    return instance;
}

}  // namespace gimbal::protocols
