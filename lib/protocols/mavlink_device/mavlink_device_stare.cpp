#include "protocols/mavlink_device/mavlink_device_stare.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "state/precision.hpp"

namespace gimbal::protocols {

using nlohmann::json;
using state::angle_deg;
using state::latlon_deg;
using state::metres;

double pointing_error_deg(const geo::Lla& point, const geo::Lla& camera,
                          const geo::Quat& line_of_sight) {
    const geo::Vec3 want =
        geo::ecef_to_ned(geo::lla_to_ecef(point) - geo::lla_to_ecef(camera), camera);
    const geo::Vec3 have = geo::rotate(line_of_sight, geo::Vec3{1, 0, 0});
    const double n = geo::norm(want) * geo::norm(have);
    if (!(n > 0)) return 180.0;
    return std::acos(std::clamp(geo::dot(want, have) / n, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

namespace {

json stare_fields(const geo::Lla& point, const StareView& view) {
    const auto& q = view.line_of_sight;
    const double range = geo::norm(geo::lla_to_ecef(point) - geo::lla_to_ecef(view.camera));
    return json{{"system_time_ms", view.time_boot_ms},
                {"along_track_stare", false},
                {"stare_started_by_time", false},
                {"gimbal_data_valid", true},
                {"lat", latlon_deg(point.lat_deg)},
                {"lon", latlon_deg(point.lon_deg)},
                {"alt", metres(point.alt_m)},
                {"gimbal_lat", latlon_deg(view.camera.lat_deg)},
                {"gimbal_lon", latlon_deg(view.camera.lon_deg)},
                {"gimbal_alt", metres(view.camera.alt_m)},
                {"gimbal_quat",
                 {state::round_decimals(q.w, 6), state::round_decimals(q.x, 6),
                  state::round_decimals(q.y, 6), state::round_decimals(q.z, 6)}},
                {"pan", view.pan_deg ? json(angle_deg(*view.pan_deg)) : json(nullptr)},
                {"tilt", angle_deg(view.tilt_deg)},
                {"slant_range", metres(range)}};
}

}  // namespace

std::optional<json> stare_start(const geo::Lla& point, const StareView& view) {
    if (pointing_error_deg(point, view.camera, view.line_of_sight) > stare_tolerance_deg)
        return std::nullopt;
    return stare_fields(point, view);
}

json path_stare_start(const sim::StareBegin& begun, const std::optional<StareView>& view) {
    const geo::Lla point = geo::ecef_to_lla(begun.point_ecef);
    json fields = view ? stare_fields(point, *view)
                       : json{{"system_time_ms", 0},
                              {"gimbal_data_valid", false},
                              {"lat", latlon_deg(point.lat_deg)},
                              {"lon", latlon_deg(point.lon_deg)},
                              {"alt", metres(point.alt_m)}};
    fields["along_track_stare"] = begun.along_track;
    fields["stare_started_by_time"] = begun.started_by_time;
    fields["prev_stare_terminated_by_time"] = begun.prev_terminated_by_time;
    fields["max_stare_time_s"] = state::round_decimals(begun.max_stare_time_s, 2);
    fields["prev_stare_time_s"] = state::round_decimals(begun.prev_stare_time_s, 2);
    fields["stare_load"] = state::round_decimals(begun.stare_load, 3);
    fields["cross_stare_angle"] = angle_deg(begun.cross_angle * 180.0 / std::numbers::pi);
    fields["slant_range"] = metres(begun.slant_range_m);
    return fields;
}

}  // namespace gimbal::protocols
