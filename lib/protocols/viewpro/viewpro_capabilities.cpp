#include "protocols/viewpro/viewpro_capabilities.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::protocols {

using nlohmann::json;
using session::number_at;

session::Features ViewproCapabilities::features() const {
    session::Features f;
    f.point_angles = true;
    return f;
}

session::Request ViewproCapabilities::point_angles(const json& state,
                                                   const session::AnglesTarget& t) const {
    const auto cur_pitch = number_at(state, {"output", "gimbal", "pitch"});
    const auto cur_yaw = number_at(state, {"output", "gimbal", "yaw"});
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

session::Request ViewproCapabilities::rate(const json&, const session::RateTarget&) const {
    return session::unsupported("Viewpro takes no rate commands");
}

session::Request ViewproCapabilities::geopoint(const json&, const session::GeoTarget&) const {
    return session::unsupported("Viewpro has no geopoint");
}

session::Request ViewproCapabilities::stop(const json&) const {
    return session::unsupported("Viewpro has no ROI");
}

session::Request ViewproCapabilities::zoom(const json&, const session::ZoomTarget&) const {
    return session::unsupported("Viewpro zoom is not supported");
}

std::optional<geo::Quat> ViewproCapabilities::line_of_sight(const json& state) const {
    // The aircraft's attitude (output.uav), then the gimbal's relative to it (output.gimbal).
    const auto uav = platform_attitude(state);
    const auto gr = number_at(state, {"output", "gimbal", "roll"});
    const auto gp = number_at(state, {"output", "gimbal", "pitch"});
    const auto gy = number_at(state, {"output", "gimbal", "yaw"});
    if (!uav || !gp || !gy) return std::nullopt;
    return geo::normalized(*uav * geo::euler_to_quat(geo::EulerDeg{gr.value_or(0), *gp, *gy}));
}

session::View ViewproCapabilities::view(const json& state) const {
    session::View v;
    v.lat_deg = number_at(state, {"output", "uav", "lat"});
    v.lon_deg = number_at(state, {"output", "uav", "lon"});
    v.alt_msl_m = number_at(state, {"output", "uav", "alt_msl"});
    v.target_lat_deg = number_at(state, {"output", "target", "lat"});
    v.target_lon_deg = number_at(state, {"output", "target", "lon"});
    v.target_alt_msl_m = number_at(state, {"output", "target", "alt_msl"});
    // The laser range finder's distance; 0 when it measures nothing.
    if (const auto lrf = number_at(state, {"output", "lrf_m"}); lrf && *lrf > 0)
        v.measured_range_m = lrf;
    return v;  // OUTx frames carry no field of view
}

command::Result<session::ImageView> ViewproCapabilities::image(const json&) const {
    // OUT1..OUT4 carry the angles but no field of view or image size: an image position
    // cannot be turned into a ray.
    return command::Error{command::code::unsupported,
                          "Viewpro output frames carry no field of view: image positions "
                          "cannot be located"};
}

std::optional<geo::Quat> ViewproCapabilities::platform_attitude(const json& state) const {
    const auto roll = number_at(state, {"output", "uav", "roll"});
    const auto pitch = number_at(state, {"output", "uav", "pitch"});
    const auto yaw = number_at(state, {"output", "uav", "yaw"});
    if (!roll || !pitch || !yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*roll, *pitch, *yaw});
}

session::Identity ViewproCapabilities::identity(const json&) const {
    return {"Viewpro", "Viewpro", std::nullopt};
}

session::Limits ViewproCapabilities::limits(const json&) const {
    return {};  // not reported
}

session::Camera ViewproCapabilities::camera(const json&) const {
    return {};
}

const ViewproCapabilities& viewpro_capabilities() {
    static const ViewproCapabilities instance;
    return instance;
}

}  // namespace gimbal::protocols
