#include "protocols/siyi/siyi_stare.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;

double siyi_pointing_error_deg(const geo::Lla& point, const geo::Lla& camera,
                               const geo::Quat& line_of_sight) {
    const geo::Vec3 want =
        geo::ecef_to_ned(geo::lla_to_ecef(point) - geo::lla_to_ecef(camera), camera);
    const geo::Vec3 have = geo::rotate(line_of_sight, geo::Vec3{1, 0, 0});
    const double lengths = geo::norm(want) * geo::norm(have);
    if (!(lengths > 0)) return 180.0;
    const double cosine = std::clamp(geo::dot(want, have) / lengths, -1.0, 1.0);
    return std::acos(cosine) * 180.0 / std::numbers::pi;
}

std::optional<json> siyi_stare_start(const geo::Lla& point, const SiyiStareView& view) {
    if (siyi_pointing_error_deg(point, view.camera, view.line_of_sight) > siyi_stare_tolerance_deg)
        return std::nullopt;
    const auto& q = view.line_of_sight;
    const auto quat = [](double c) { return state::round_decimals(c, 6); };
    return json{{"system_time_ms", view.system_time_ms},
                {"along_track_stare", false},
                {"stare_started_by_time", false},
                {"gimbal_data_valid", true},
                {"lat", state::latlon_deg(point.lat_deg)},
                {"lon", state::latlon_deg(point.lon_deg)},
                {"alt", state::metres(point.alt_m)},
                {"gimbal_lat", state::latlon_deg(view.camera.lat_deg)},
                {"gimbal_lon", state::latlon_deg(view.camera.lon_deg)},
                {"gimbal_alt", state::metres(view.camera.alt_m)},
                {"gimbal_quat", {quat(q.w), quat(q.x), quat(q.y), quat(q.z)}},
                {"pan", state::angle_deg(view.pan_deg)},
                {"tilt", state::angle_deg(view.tilt_deg)},
                {"slant_range", state::metres(geo::norm(geo::lla_to_ecef(point) -
                                                        geo::lla_to_ecef(view.camera)))}};
}

}  // namespace gimbal::protocols
