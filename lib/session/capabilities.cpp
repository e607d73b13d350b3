#include "session/capabilities.hpp"

#include <cmath>

namespace gimbal::session {

std::vector<std::string> feature_names(const Features& f) {
    std::vector<std::string> out;
    if (f.point_angles) out.emplace_back("point_angles");
    if (f.rate) out.emplace_back("rate");
    if (f.geopoint) out.emplace_back("geopoint");
    if (f.zoom) out.emplace_back("zoom");
    return out;
}

double wrap180(double deg) {
    double d = std::fmod(deg + 180.0, 360.0);
    if (d < 0) d += 360.0;
    return d - 180.0;
}

Request unsupported(std::string message) {
    return Request{command::ErrorCode::unsupported, std::move(message)};
}

Request unavailable(std::string message) {
    return Request{command::ErrorCode::unavailable, std::move(message)};
}

Request nose_angles_request(const AnglesTarget& t, const state::Telemetry* current,
                            std::string_view who) {
    // The current angles are read in place: copying a disengaged optional<double> makes GCC
    // 12 at -O2 warn (-Wmaybe-uninitialized) about its unset value.
    const bool have_pan = current && current->pan, have_tilt = current && current->tilt;
    const std::string not_yet =
        "no attitude from the " + std::string(who) + " yet for the angle left out";
    double pan = 0;
    if (t.yaw_deg && t.yaw_frame == YawFrame::earth) {
        if (!t.vehicle_heading_deg)
            return unavailable("yaw from north needs the aircraft's heading");
        pan = wrap180(*t.yaw_deg - *t.vehicle_heading_deg);
    } else if (t.yaw_deg) {
        pan = *t.yaw_deg;
    } else if (have_pan) {
        pan = *current->pan;
    } else {
        return unavailable(not_yet);
    }
    double tilt = 0;
    if (t.pitch_deg)
        tilt = *t.pitch_deg;
    else if (have_tilt)
        tilt = *current->tilt;
    else
        return unavailable(not_yet);
    return nlohmann::json{{"cmd", "position"}, {"pan", pan}, {"tilt", tilt}};
}

Request nose_rate_request(const RateTarget& t) {
    return nlohmann::json{{"cmd", "rate"},
                          {"pan", std::isnan(t.yaw_dps) ? 0.0 : t.yaw_dps},
                          {"tilt", std::isnan(t.pitch_dps) ? 0.0 : t.pitch_dps}};
}

Request msl_geopoint_request(const GeoTarget& t) {
    return nlohmann::json{{"cmd", "geopoint"},
                          {"lat", t.lat_deg},
                          {"lon", t.lon_deg},
                          {"alt", t.alt_msl_m},
                          {"alt_ref", "msl"}};
}

Request stop_rates_request() {
    return nlohmann::json{{"cmd", "rate"}, {"pan", 0.0}, {"tilt", 0.0}};
}

}  // namespace gimbal::session
