#include "protocols/orion/orion_capabilities.hpp"

#include <cmath>
#include <string>

#include "geo/image.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using session::number_at;
using session::state_at;

namespace {

// The first camera's zoom range as a ratio (max / min focal length); 1 when unknown.
double max_zoom_ratio(const json* cams) {
    if (!cams || !cams->is_array() || cams->empty()) return 1.0;
    const auto lo = number_at((*cams)[0], {"min_focal_length_mm"});
    const auto hi = number_at((*cams)[0], {"max_focal_length_mm"});
    return lo && hi && *lo > 0 && *hi >= *lo ? *hi / *lo : 1.0;
}

// LIMITS min_pos / max_pos: [pan, tilt] in degrees.
std::optional<double> limit(const json& state, const char* key, std::size_t axis) {
    const json* v = state_at(state, {"limits", key});
    if (!v || !v->is_array() || v->size() <= axis || !(*v)[axis].is_number()) return std::nullopt;
    return (*v)[axis].get<double>();
}

// The telemetry's mount quaternion (mount -> NED), when it holds four finite numbers.
std::optional<geo::Quat> mount_quat(const json& state) {
    const json* q = state_at(state, {"telemetry", "quat"});
    if (!q || !q->is_array() || q->size() != 4) return std::nullopt;
    geo::Quat mount;
    double* parts[] = {&mount.w, &mount.x, &mount.y, &mount.z};
    for (std::size_t i = 0; i < 4; ++i) {
        if (!(*q)[i].is_number()) return std::nullopt;
        *parts[i] = (*q)[i].get<double>();
        if (!std::isfinite(*parts[i])) return std::nullopt;
    }
    return mount;
}

}  // namespace

session::Features OrionCapabilities::features() const {
    session::Features f;
    f.point_angles = f.rate = f.geopoint = f.zoom = true;
    f.pitch_lock = f.yaw_lock = f.yaw_in_earth_frame = f.infinite_yaw = true;
    f.absolute_angles = true;
    return f;
}

session::Request OrionCapabilities::point_angles(const json& state,
                                                 const session::AnglesTarget& t) const {
    double pan = 0;
    double tilt = 0;
    if (!t.yaw_deg || !t.pitch_deg) {
        // The angle left out stays where the gimbal points now (in its own, vehicle frame).
        const auto cur_pan = number_at(state, {"telemetry", "pan"});
        const auto cur_tilt = number_at(state, {"telemetry", "tilt"});
        if (!cur_pan || !cur_tilt)
            return session::unavailable("no telemetry yet for the angle left out");
        pan = t.yaw_deg.value_or(*cur_pan);
        tilt = t.pitch_deg.value_or(*cur_tilt);
    } else {
        pan = *t.yaw_deg;
        tilt = *t.pitch_deg;
        if (t.yaw_frame == session::YawFrame::earth) {
            if (!t.vehicle_heading_deg)
                return session::unavailable("yaw from north needs the aircraft's heading");
            pan = session::wrap180(*t.yaw_deg - *t.vehicle_heading_deg);
        }
    }
    return json{{"cmd", "position"}, {"pan", pan}, {"tilt", tilt}};
}

session::Request OrionCapabilities::rate(const json&, const session::RateTarget& t) const {
    return json{{"cmd", "rate"},
                {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

session::Request OrionCapabilities::geopoint(const json&, const session::GeoTarget& t) const {
    return json{{"cmd", "geopoint"},
                {"lat", t.lat_deg},
                {"lon", t.lon_deg},
                {"alt", t.alt_msl_m},
                {"alt_ref", "msl"}};
}

session::Request OrionCapabilities::stop(const json&) const {
    return json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}, {"stabilized", true}};
}

session::Request OrionCapabilities::zoom(const json& state, const session::ZoomTarget& t) const {
    // OrionCameraState takes a zoom ratio, not a rate: continuous zoom goes all the way.
    const json* cams = state_at(state, {"cameras", "cameras"});
    const double max_ratio = max_zoom_ratio(cams);
    double ratio = 1.0;
    switch (t.kind) {
        case session::ZoomKind::range_percent:
            if (!cams) return session::unavailable("camera list not known yet");
            ratio = 1.0 + (max_ratio - 1.0) * t.value / 100.0;
            break;
        case session::ZoomKind::continuous:
            if (t.value > 0 && !cams) return session::unavailable("camera list not known yet");
            ratio = t.value > 0 ? max_ratio : 1.0;
            break;
    }
    return json{{"cmd", "camera_zoom"}, {"zoom", std::round(ratio * 100) / 100}};
}

std::optional<geo::Quat> OrionCapabilities::line_of_sight(const json& state) const {
    // The mount quaternion, then pan about the mount's z and tilt about the new y.
    const auto pan = number_at(state, {"telemetry", "pan"});
    const auto tilt = number_at(state, {"telemetry", "tilt"});
    const auto mount = mount_quat(state);
    if (!pan || !tilt || !mount) return std::nullopt;
    return geo::normalized(geo::normalized(*mount) *
                           geo::euler_to_quat(geo::EulerDeg{0, *tilt, *pan}));
}

session::View OrionCapabilities::view(const json& state) const {
    session::View v;
    v.lat_deg = number_at(state, {"telemetry", "lat"});
    v.lon_deg = number_at(state, {"telemetry", "lon"});
    v.alt_msl_m = number_at(state, {"telemetry", "alt_msl"});
    v.target_lat_deg = number_at(state, {"telemetry", "target", "lat"});
    v.target_lon_deg = number_at(state, {"telemetry", "target", "lon"});
    // The target's altitude is WGS84: MSL is it minus the geoid undulation.
    const auto alt = number_at(state, {"telemetry", "target", "alt"});
    const auto n = number_at(state, {"telemetry", "geoid_undulation"});
    if (alt && n) v.target_alt_msl_m = *alt - *n;
    v.hfov_deg = number_at(state, {"telemetry", "hfov"});
    v.vfov_deg = number_at(state, {"telemetry", "vfov"});
    v.alt_m = number_at(state, {"telemetry", "alt"});
    // With range_source "laser" the line-of-sight vector is the laser's range (Orion ICD).
    const json* source = state_at(state, {"telemetry", "range_source"});
    const json* los = state_at(state, {"telemetry", "los_ecef"});
    if (source && *source == "laser" && los && los->is_array() && los->size() == 3 &&
        v.target_lat_deg) {
        double sum = 0;
        for (const auto& c : *los) sum += c.is_number() ? c.get<double>() * c.get<double>() : 0;
        if (sum > 0) v.measured_range_m = std::sqrt(sum);
    }
    return v;
}

command::Result<session::ImageView> OrionCapabilities::image(const json& state) const {
    // GeolocateTelemetry: the gimbal's position, mount quaternion, pan/tilt and fields of
    // view; no image rotation. The flat world is the target's altitude.
    const auto lat = number_at(state, {"telemetry", "lat"});
    const auto lon = number_at(state, {"telemetry", "lon"});
    const auto alt = number_at(state, {"telemetry", "alt"});
    const auto pan = number_at(state, {"telemetry", "pan"});
    const auto tilt = number_at(state, {"telemetry", "tilt"});
    const auto hfov = number_at(state, {"telemetry", "hfov"});
    const auto vfov = number_at(state, {"telemetry", "vfov"});
    const auto mount = mount_quat(state);
    if (!lat || !lon || !alt || !pan || !tilt || !hfov || !vfov || !mount)
        return command::Error{command::code::unavailable, "no telemetry from the gimbal yet"};
    session::ImageView v;
    v.camera = geo::camera_pose({*lat, *lon, *alt}, *mount, *pan, *tilt, *hfov, *vfov);
    if (!geo::valid(v.camera))
        return command::Error{command::code::unavailable,
                              "the telemetry's field of view is not usable (hfov " +
                                  std::to_string(*hfov) + ", vfov " + std::to_string(*vfov) +
                                  " degrees)"};
    const auto w = number_at(state, {"telemetry", "pixel_width"});
    const auto h = number_at(state, {"telemetry", "pixel_height"});
    if (w && h && *w > 0 && *h > 0) {
        v.width_px = *w;
        v.height_px = *h;
    }
    v.flat_alt_m = number_at(state, {"telemetry", "target", "alt"});
    // geopoint's alt_ref msl converts with the telemetry's undulation.
    v.geoid_undulation_m = number_at(state, {"telemetry", "geoid_undulation"});
    return v;
}

std::optional<geo::Quat> OrionCapabilities::platform_attitude(const json& state) const {
    // The mount quaternion: the gimbal is fixed to the aircraft.
    const auto mount = mount_quat(state);
    if (!mount) return std::nullopt;
    return geo::normalized(*mount);
}

session::Identity OrionCapabilities::identity(const json& state) const {
    session::Identity id{"Trillium", "Orion", std::nullopt};
    const json* version = state_at(state, {"versions", "crown", "version"});
    if (version && version->is_string() && !version->get_ref<const std::string&>().empty())
        id.firmware = version->get<std::string>();
    return id;
}

session::Limits OrionCapabilities::limits(const json& state) const {
    return {limit(state, "min_pos", 0), limit(state, "max_pos", 0), limit(state, "min_pos", 1),
            limit(state, "max_pos", 1)};
}

session::Camera OrionCapabilities::camera(const json& state) const {
    session::Camera c;
    c.basic_zoom = true;
    const json* cams = state_at(state, {"cameras", "cameras"});
    if (!cams || !cams->is_array() || cams->empty()) return c;
    const json& cam = (*cams)[0];
    c.focal_length_mm = number_at(cam, {"min_focal_length_mm"});
    const auto w = number_at(cam, {"array_width"});
    const auto h = number_at(cam, {"array_height"});
    const auto pitch = number_at(cam, {"pixel_pitch_mm"});
    if (w && h) {
        c.width_px = static_cast<int>(*w);
        c.height_px = static_cast<int>(*h);
        if (pitch) {
            c.sensor_width_mm = *w * *pitch;
            c.sensor_height_mm = *h * *pitch;
        }
    }
    return c;
}

const OrionCapabilities& orion_capabilities() {
    static const OrionCapabilities instance;
    return instance;
}

}  // namespace gimbal::protocols
