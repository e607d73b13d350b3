#include "protocols/orion/orion_capabilities.hpp"

#include <cmath>
#include <string>

#include "geo/image.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using state::shown;

namespace {

namespace o = gimbal::orion;

// The first camera's zoom range as a ratio (max / min focal length); 1 when unknown.
double max_zoom_ratio(const o::Cameras& cams) {
    if (cams.cameras.empty()) return 1.0;
    const auto& cam = cams.cameras[0];
    const auto lo = shown(cam, cam.min_focal_length_mm);
    const auto hi = shown(cam, cam.max_focal_length_mm);
    return lo && hi && *lo > 0 && *hi >= *lo ? *hi / *lo : 1.0;
}

}  // namespace

session::Features orion_features() {
    session::Features f;
    f.point_angles = f.rate = f.geopoint = f.zoom = true;
    f.pitch_lock = f.yaw_lock = f.yaw_in_earth_frame = f.infinite_yaw = true;
    f.absolute_angles = true;
    return f;
}

const state::Telemetry* OrionCapabilities::shared() const {
    return data_.telemetry ? &data_.telemetry->shared : nullptr;
}

// The telemetry's mount quaternion (mount -> NED), when it holds four finite numbers.
std::optional<geo::Quat> OrionCapabilities::mount() const {
    if (!data_.telemetry) return std::nullopt;
    const auto& t = data_.telemetry->packet;
    geo::Quat q;
    double* parts[] = {&q.w, &q.x, &q.y, &q.z};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto c = shown(t, t.quat, i);
        if (!c) return std::nullopt;
        *parts[i] = *c;
    }
    return q;
}

session::Request OrionCapabilities::point_angles(const session::AnglesTarget& t) const {
    double pan = 0;
    double tilt = 0;
    if (!t.yaw_deg || !t.pitch_deg) {
        // The angle left out stays where the gimbal points now (in its own, vehicle frame).
        const auto* s = shared();
        if (!s || !s->pan || !s->tilt)
            return session::unavailable("no telemetry yet for the angle left out");
        pan = t.yaw_deg.value_or(*s->pan);
        tilt = t.pitch_deg.value_or(*s->tilt);
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

session::Request OrionCapabilities::rate(const session::RateTarget& t) const {
    return json{{"cmd", "rate"},
                {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

session::Request OrionCapabilities::geopoint(const session::GeoTarget& t) const {
    return json{{"cmd", "geopoint"},
                {"lat", t.lat_deg},
                {"lon", t.lon_deg},
                {"alt", t.alt_msl_m},
                {"alt_ref", "msl"}};
}

session::Request OrionCapabilities::stop() const {
    return json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}, {"stabilized", true}};
}

session::Request OrionCapabilities::zoom(const session::ZoomTarget& t) const {
    // OrionCameraState takes a zoom ratio, not a rate: continuous zoom goes all the way.
    const auto& cams = data_.packets.cameras;
    const double max_ratio = cams ? max_zoom_ratio(cams->packet) : 1.0;
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

std::optional<geo::Quat> OrionCapabilities::line_of_sight() const {
    // The mount quaternion, then pan about the mount's z and tilt about the new y.
    const auto* s = shared();
    const auto m = mount();
    if (!s || !s->pan || !s->tilt || !m) return std::nullopt;
    return geo::normalized(geo::normalized(*m) *
                           geo::euler_to_quat(geo::EulerDeg{0, *s->tilt, *s->pan}));
}

session::View OrionCapabilities::view() const {
    session::View v;
    const auto* s = shared();
    if (!s) return v;
    v.lat_deg = s->lat;
    v.lon_deg = s->lon;
    v.alt_msl_m = s->alt_msl;
    if (s->target) {
        v.target_lat_deg = s->target->lat;
        v.target_lon_deg = s->target->lon;
        // The target's altitude is WGS84: MSL is it minus the geoid undulation.
        if (s->geoid_undulation) v.target_alt_msl_m = s->target->alt - *s->geoid_undulation;
    }
    v.hfov_deg = s->hfov;
    v.vfov_deg = s->vfov;
    v.alt_m = s->alt;
    // With range_source "laser" the line-of-sight vector is the laser's range (Orion ICD).
    const auto& t = data_.telemetry->packet;
    if (t.range_source == o::RangeSource::laser && v.target_lat_deg) {
        double sum = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            const double c = shown(t, t.los_ecef, i).value_or(0.0);
            sum += c * c;
        }
        if (sum > 0) v.measured_range_m = std::sqrt(sum);
    }
    return v;
}

command::Result<session::ImageView> OrionCapabilities::image() const {
    // GeolocateTelemetry: the gimbal's position, mount quaternion, pan/tilt and fields of
    // view; no image rotation. The flat world is the target's altitude.
    const auto* s = shared();
    const auto m = mount();
    if (!s || !s->lat || !s->lon || !s->alt || !s->pan || !s->tilt || !s->hfov || !s->vfov || !m)
        return command::Error{command::code::unavailable, "no telemetry from the gimbal yet"};
    session::ImageView v;
    v.camera =
        geo::camera_pose({*s->lat, *s->lon, *s->alt}, *m, *s->pan, *s->tilt, *s->hfov, *s->vfov);
    if (!geo::valid(v.camera))
        return command::Error{command::code::unavailable,
                              "the telemetry's field of view is not usable (hfov " +
                                  std::to_string(*s->hfov) + ", vfov " + std::to_string(*s->vfov) +
                                  " degrees)"};
    const auto& t = data_.telemetry->packet;
    const auto w = shown(t, t.pixel_width);
    const auto h = shown(t, t.pixel_height);
    if (w && h && *w > 0 && *h > 0) {
        v.width_px = *w;
        v.height_px = *h;
    }
    if (s->target) v.flat_alt_m = s->target->alt;
    // geopoint's alt_ref msl converts with the telemetry's undulation.
    v.geoid_undulation_m = s->geoid_undulation;
    return v;
}

std::optional<geo::Quat> OrionCapabilities::platform_attitude() const {
    // The mount quaternion: the gimbal is fixed to the aircraft.
    const auto m = mount();
    if (!m) return std::nullopt;
    return geo::normalized(*m);
}

session::Identity OrionCapabilities::identity() const {
    session::Identity id{"Trillium", "Orion", std::nullopt};
    if (const auto& crown = data_.packets.crown_version) {
        std::string version = o::printable(crown->packet.version);
        if (!version.empty()) id.firmware = std::move(version);
    }
    return id;
}

session::Limits OrionCapabilities::limits() const {
    const auto& l = data_.packets.limits;
    if (!l) return {};
    const auto& p = l->packet;
    // LIMITS min_pos / max_pos: [pan, tilt] in degrees.
    return {shown(p, p.min_pos, 0), shown(p, p.max_pos, 0), shown(p, p.min_pos, 1),
            shown(p, p.max_pos, 1)};
}

session::Camera OrionCapabilities::camera() const {
    session::Camera c;
    c.basic_zoom = true;
    const auto& cams = data_.packets.cameras;
    if (!cams || cams->packet.cameras.empty()) return c;
    const auto& cam = cams->packet.cameras[0];
    c.focal_length_mm = shown(cam, cam.min_focal_length_mm);
    const auto w = shown(cam, cam.array_width);
    const auto h = shown(cam, cam.array_height);
    const auto pitch = shown(cam, cam.pixel_pitch_mm);
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

std::optional<bool> OrionCapabilities::holds_geopoint() const {
    // A mode the ICD does not name says nothing.
    if (!data_.telemetry) return std::nullopt;
    const o::Mode mode = data_.telemetry->packet.mode;
    if (o::enum_name(mode).empty()) return std::nullopt;
    return mode == o::Mode::geopoint;
}

}  // namespace gimbal::protocols
