#include "protocols/siyi/siyi_capabilities.hpp"

#include <algorithm>
#include <cmath>

#include "geo/wgs84.hpp"
#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using state::angle_deg;

session::Features siyi_features() {
    session::Features f;
    f.point_angles = f.rate = f.geopoint = f.zoom = true;
    f.pitch_lock = true;  // SIYI's pitch is held in the earth frame in every motion mode
    f.absolute_angles = true;
    return f;
}

session::Request SiyiCapabilities::point_angles(const session::AnglesTarget& t) const {
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
        return session::unavailable("no attitude from the camera yet for the angle left out");
    }
    double tilt = 0;
    if (t.pitch_deg)
        tilt = *t.pitch_deg;
    else if (have_tilt)
        tilt = *tel->tilt;
    else
        return session::unavailable("no attitude from the camera yet for the angle left out");
    return json{{"cmd", "position"}, {"pan", pan}, {"tilt", tilt}};
}

session::Request SiyiCapabilities::rate(const session::RateTarget& t) const {
    return json{{"cmd", "rate"},
                {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

session::Request SiyiCapabilities::geopoint(const session::GeoTarget& t) const {
    return json{{"cmd", "geopoint"},
                {"lat", t.lat_deg},
                {"lon", t.lon_deg},
                {"alt", t.alt_msl_m},
                {"alt_ref", "msl"}};
}

session::Request SiyiCapabilities::stop() const {
    return json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}};
}

// Percent of the zoom range as the ratio 0x0F takes (one decimal). Continuous zoom (0x05)
// has no catalogue command: a caller asks for a percentage instead.
session::Request SiyiCapabilities::zoom(const session::ZoomTarget& t) const {
    if (t.kind == session::ZoomKind::continuous)
        return session::unsupported("a SIYI camera zooms to a ratio here, not continuously");
    const double max =
        data_.zoom_max.value_or(siyi::model_info(data_.model.value_or(siyi::Model::zt30)).zoom_max);
    const double pct = std::clamp(t.value, 0.0, 100.0);
    const double ratio = std::round((1.0 + (max - 1.0) * pct / 100.0) * 10.0) / 10.0;
    return json{{"cmd", "camera_zoom"}, {"zoom", ratio}};
}

std::optional<geo::Quat> SiyiCapabilities::line_of_sight() const {
    const auto* t = data_.telemetry ? &*data_.telemetry : nullptr;
    if (!data_.attitude || !t || !t->yaw) return std::nullopt;
    const SiyiAttitude& a = *data_.attitude;
    return geo::normalized(geo::euler_to_quat(
        geo::EulerDeg{0, angle_deg(a.tilt_deg), session::wrap180(*t->yaw + angle_deg(a.pan_deg))}));
}

session::View SiyiCapabilities::view() const {
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
    v.measured_range_m = data_.laser_range_m;
    return v;
}

command::Result<session::ImageView> SiyiCapabilities::image() const {
    const auto* t = data_.telemetry ? &*data_.telemetry : nullptr;
    const auto los = line_of_sight();
    if (!t || !t->lat || !t->lon || !t->alt || !t->hfov || !t->vfov || !los)
        return command::Error{command::code::unavailable,
                              "no camera attitude with a vehicle position yet"};
    session::ImageView v;
    v.camera = geo::CameraPose{{*t->lat, *t->lon, *t->alt}, *los, *t->hfov, *t->vfov};
    if (t->target) v.flat_alt_m = t->target->alt;
    v.geoid_undulation_m = t->geoid_undulation;
    return v;
}

std::optional<geo::Quat> SiyiCapabilities::platform_attitude() const {
    const auto* t = data_.telemetry ? &*data_.telemetry : nullptr;
    if (!t || !t->roll || !t->pitch || !t->yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*t->roll, *t->pitch, *t->yaw});
}

session::Identity SiyiCapabilities::identity() const {
    session::Identity i{"SIYI", "gimbal camera", std::nullopt};
    if (data_.model) i.model = std::string(siyi::model_info(*data_.model).name);
    if (data_.firmware) i.firmware = data_.firmware->gimbal;
    return i;
}

// The model's table in gimbald's frame: pan is the negated SIYI yaw.
session::Limits SiyiCapabilities::limits() const {
    if (!data_.model) return {};
    const siyi::ModelInfo& m = siyi::model_info(*data_.model);
    session::Limits l;
    if (!m.yaw_continuous) {
        l.pan_min_deg = -m.yaw_max;
        l.pan_max_deg = -m.yaw_min;
    }
    l.tilt_min_deg = m.pitch_min;
    l.tilt_max_deg = m.pitch_max;
    return l;
}

session::Camera SiyiCapabilities::camera() const {
    session::Camera c;
    c.basic_zoom = true;
    return c;
}

}  // namespace gimbal::protocols
