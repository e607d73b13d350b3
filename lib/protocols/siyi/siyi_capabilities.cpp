#include "protocols/siyi/siyi_capabilities.hpp"

#include <algorithm>
#include <cmath>

#include "geo/wgs84.hpp"
#include "session/aimed_telemetry.hpp"
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
    return session::nose_angles_request(t, data_.telemetry ? &*data_.telemetry : nullptr, "camera");
}

session::Request SiyiCapabilities::rate(const session::RateTarget& t) const {
    return session::nose_rate_request(t);
}

session::Request SiyiCapabilities::geopoint(const session::GeoTarget& t) const {
    return session::msl_geopoint_request(t);
}

session::Request SiyiCapabilities::stop() const {
    return session::stop_rates_request();
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
    session::View v = session::view_from(data_.telemetry ? &*data_.telemetry : nullptr);
    v.measured_range_m = data_.laser_range_m;
    return v;
}

command::Result<session::ImageView> SiyiCapabilities::image() const {
    return session::image_from(data_.telemetry ? &*data_.telemetry : nullptr, line_of_sight(),
                               "camera");
}

std::optional<geo::Quat> SiyiCapabilities::platform_attitude() const {
    return session::aircraft_attitude_from(data_.telemetry ? &*data_.telemetry : nullptr);
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
