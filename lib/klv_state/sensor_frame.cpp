#include "klv_state/sensor_frame.hpp"

#include <cmath>

#include "geo/wgs84.hpp"
#include "klv_state/track_vmti.hpp"

namespace gimbal::klv_state {

using nlohmann::json;

namespace {

std::optional<klv::GroundPoint> ground_point(const state::Telemetry* t,
                                             const std::optional<double>& undulation_m,
                                             std::optional<double>& range_m) {
    if (!t || !t->view.ground) return std::nullopt;
    const geo::GroundPoint& g = *t->view.ground;
    klv::GroundPoint p{g.point.lat_deg, g.point.lon_deg, std::nullopt};
    if (undulation_m) p.alt_msl_m = geo::msl_from_ellipsoid(g.point.alt_m, *undulation_m);
    range_m = g.range_m;
    return p;
}

std::optional<std::array<klv::LatLon, 4>> footprint(const state::Telemetry* t) {
    if (!t || !t->view.footprint) return std::nullopt;
    std::array<klv::LatLon, 4> corners{};
    for (std::size_t i = 0; i < 4; ++i)
        corners[i] = {(*t->view.footprint)[i].lat, (*t->view.footprint)[i].lon};
    return corners;
}

// Distance between two points given as latitude, longitude and (when both have one) altitude;
// without altitudes both are taken at height 0 (the distance along the ground, near enough).
double distance_m(double lat1, double lon1, std::optional<double> alt1, double lat2, double lon2,
                  std::optional<double> alt2) {
    const bool heights = alt1 && alt2;
    const geo::Vec3 a = geo::lla_to_ecef({lat1, lon1, heights ? *alt1 : 0.0});
    const geo::Vec3 b = geo::lla_to_ecef({lat2, lon2, heights ? *alt2 : 0.0});
    return geo::norm(a - b);
}

// A number of the decoded KLV (lib/klv's JSON of a set).
std::optional<double> number(const json& j, const char* key) {
    const auto it = j.is_object() ? j.find(key) : j.end();
    if (!j.is_object() || it == j.end() || !it->is_number()) return std::nullopt;
    const double d = it->get<double>();
    return std::isfinite(d) ? std::optional(d) : std::nullopt;
}

// Contract section 20: the track's ground position is the target location (40-42) and the
// track is the VMTI set (74). The frame centre stays the image centre's.
void add_track(klv::SensorFrame& f, const state::TrackState& track,
               const session::GimbalView& gimbal, const std::optional<double>& undulation_m) {
    if (track.ground && std::isfinite(track.ground->lat) && std::isfinite(track.ground->lon)) {
        klv::GroundPoint p{track.ground->lat, track.ground->lon, std::nullopt};
        if (undulation_m && std::isfinite(track.ground->alt))
            p.alt_msl_m = geo::msl_from_ellipsoid(track.ground->alt, *undulation_m);
        f.target = p;
    }
    const std::optional<state::VideoState> video =
        gimbal.video ? gimbal.video() : std::optional<state::VideoState>();
    if (video) f.vmti = track_vmti(track, video->width, video->height);
}

}  // namespace

klv::SensorFrame sensor_frame(const session::GimbalView& gimbal, std::uint64_t time_us,
                              const std::optional<std::string>& mission_id) {
    const session::Capabilities& caps = *gimbal.capabilities;
    klv::SensorFrame f;
    f.time_us = time_us;
    f.mission_id = mission_id;
    const session::View view = caps.view();
    f.sensor_lat_deg = view.lat_deg;
    f.sensor_lon_deg = view.lon_deg;
    f.sensor_alt_msl_m = view.alt_msl_m;
    f.hfov_deg = view.hfov_deg;
    f.vfov_deg = view.vfov_deg;

    const auto platform = caps.platform_attitude();
    if (platform) {
        const geo::EulerDeg e = geo::quat_to_euler(*platform);
        f.platform_heading_deg = e.yaw_deg;
        f.platform_pitch_deg = e.pitch_deg;
        f.platform_roll_deg = e.roll_deg;
        if (const auto los = caps.line_of_sight()) {
            // The line of sight in the platform's axes: azimuth from the nose, elevation up.
            const geo::EulerDeg r =
                geo::quat_to_euler(geo::normalized(geo::conjugate(*platform) * *los));
            f.relative_azimuth_deg = r.yaw_deg;
            f.relative_elevation_deg = r.pitch_deg;
            f.relative_roll_deg = r.roll_deg;
        }
    }

    std::optional<double> undulation;
    if (view.alt_m && view.alt_msl_m) undulation = *view.alt_m - *view.alt_msl_m;
    std::optional<double> ground_range;
    f.frame_center = ground_point(gimbal.telemetry, undulation, ground_range);
    const bool target_known = view.target_lat_deg && view.target_lon_deg;
    if (target_known)
        f.target =
            klv::GroundPoint{*view.target_lat_deg, *view.target_lon_deg, view.target_alt_msl_m};
    if (!f.frame_center) f.frame_center = f.target;
    if (f.frame_center) f.corners = footprint(gimbal.telemetry);
    if (const auto track = gimbal.track ? gimbal.track() : std::nullopt)
        add_track(f, *track, gimbal, undulation);

    if (view.measured_range_m) {
        f.slant_range_m = view.measured_range_m;
        f.slant_range_measured = true;
    } else if (ground_range) {
        f.slant_range_m = ground_range;
    } else if (f.frame_center && f.frame_center->alt_msl_m && has_position(f) &&
               f.sensor_alt_msl_m) {
        f.slant_range_m =
            distance_m(*f.sensor_lat_deg, *f.sensor_lon_deg, f.sensor_alt_msl_m,
                       f.frame_center->lat_deg, f.frame_center->lon_deg, f.frame_center->alt_msl_m);
    }
    return f;
}

bool has_position(const klv::SensorFrame& frame) {
    return frame.sensor_lat_deg && frame.sensor_lon_deg && std::isfinite(*frame.sensor_lat_deg) &&
           std::isfinite(*frame.sensor_lon_deg);
}

state::KlvOffsets compare(const json& decoded, const klv::SensorFrame& own) {
    state::KlvOffsets out;
    const auto s_lat = number(decoded, "sensor_latitude");
    const auto s_lon = number(decoded, "sensor_longitude");
    if (s_lat && s_lon && has_position(own))
        out.sensor_m = distance_m(*s_lat, *s_lon, number(decoded, "sensor_true_altitude"),
                                  *own.sensor_lat_deg, *own.sensor_lon_deg, own.sensor_alt_msl_m);
    const auto c_lat = number(decoded, "frame_center_latitude");
    const auto c_lon = number(decoded, "frame_center_longitude");
    if (c_lat && c_lon && own.frame_center)
        out.frame_center_m = distance_m(*c_lat, *c_lon, number(decoded, "frame_center_elevation"),
                                        own.frame_center->lat_deg, own.frame_center->lon_deg,
                                        own.frame_center->alt_msl_m);
    return out;
}

}  // namespace gimbal::klv_state
