#include "protocols/viewpro/viewpro_capabilities.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::protocols {

using nlohmann::json;

namespace {

// A reported value that is a number (a frame's field may be absent).
std::optional<double> finite(const std::optional<double>& v) {
    return v && std::isfinite(*v) ? v : std::nullopt;
}

}  // namespace

session::Features viewpro_features() {
    session::Features f;
    f.point_angles = true;
    return f;
}

session::Request ViewproCapabilities::point_angles(const session::AnglesTarget& t) const {
    const auto cur_pitch = output_ ? finite(output_->gimbal_pitch_deg) : std::nullopt;
    const auto cur_yaw = output_ ? finite(output_->gimbal_yaw_deg) : std::nullopt;
    if (!cur_pitch || !cur_yaw) return session::unavailable("no Viewpro angles reported yet");
    double yaw = t.yaw_deg.value_or(*cur_yaw);
    if (t.yaw_frame == session::YawFrame::earth && t.yaw_deg) {
        if (!t.vehicle_heading_deg)
            return session::unavailable("yaw from north needs the aircraft's heading");
        yaw = session::wrap180(*t.yaw_deg - *t.vehicle_heading_deg);
    }
    const double pitch = t.pitch_deg.value_or(*cur_pitch);
    // One adjust command moves at most 20 degrees per axis: a larger move converges over the
    // next commands (a ground station repeats them).
    const auto step = [](double d) { return std::round(std::clamp(d, -20.0, 20.0) * 100) / 100; };
    const double dyaw = step(session::wrap180(yaw - *cur_yaw));
    const double dpitch = step(pitch - *cur_pitch);
    json r = {{"cmd", "viewpro_adjust"}};
    if (dyaw != 0) r["yaw_deg"] = dyaw;
    if (dpitch != 0 || dyaw == 0) r["pitch_deg"] = dpitch;
    return r;
}

session::Request ViewproCapabilities::rate(const session::RateTarget&) const {
    return session::unsupported("Viewpro takes no rate commands");
}

session::Request ViewproCapabilities::geopoint(const session::GeoTarget&) const {
    return session::unsupported("Viewpro has no geopoint");
}

session::Request ViewproCapabilities::stop() const {
    return session::unsupported("Viewpro has no ROI");
}

session::Request ViewproCapabilities::zoom(const session::ZoomTarget&) const {
    return session::unsupported("Viewpro zoom is not supported");
}

std::optional<geo::Quat> ViewproCapabilities::line_of_sight() const {
    // The aircraft's attitude (output.uav), then the gimbal's relative to it (output.gimbal).
    const auto uav = platform_attitude();
    if (!uav) return std::nullopt;
    const auto gr = finite(output_->gimbal_roll_deg);
    const auto gp = finite(output_->gimbal_pitch_deg);
    const auto gy = finite(output_->gimbal_yaw_deg);
    if (!gp || !gy) return std::nullopt;
    return geo::normalized(*uav * geo::euler_to_quat(geo::EulerDeg{gr.value_or(0), *gp, *gy}));
}

session::View ViewproCapabilities::view() const {
    session::View v;
    if (!output_) return v;
    const auto& o = *output_;
    v.lat_deg = finite(o.uav_lat_deg);
    v.lon_deg = finite(o.uav_lon_deg);
    v.alt_msl_m = finite(o.uav_alt_msl_m);
    v.target_lat_deg = finite(o.target_lat_deg);
    v.target_lon_deg = finite(o.target_lon_deg);
    v.target_alt_msl_m = finite(o.target_alt_msl_m);
    // The laser range finder's distance; 0 when it measures nothing.
    if (const auto lrf = finite(o.lrf_m); lrf && *lrf > 0) v.measured_range_m = lrf;
    return v;  // OUTx frames carry no field of view
}

command::Result<session::ImageView> ViewproCapabilities::image() const {
    // OUT1..OUT4 carry the angles but no field of view or image size: an image position
    // cannot be turned into a ray.
    return command::Error{command::code::unsupported,
                          "Viewpro output frames carry no field of view: image positions "
                          "cannot be located"};
}

std::optional<geo::Quat> ViewproCapabilities::platform_attitude() const {
    if (!output_) return std::nullopt;
    const auto roll = finite(output_->uav_roll_deg);
    const auto pitch = finite(output_->uav_pitch_deg);
    const auto yaw = finite(output_->uav_yaw_deg);
    if (!roll || !pitch || !yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*roll, *pitch, *yaw});
}

session::Identity ViewproCapabilities::identity() const {
    return {"Viewpro", "Viewpro", std::nullopt};
}

session::Limits ViewproCapabilities::limits() const {
    return {};  // not reported
}

session::Camera ViewproCapabilities::camera() const {
    return {};
}

}  // namespace gimbal::protocols
