#include "session/aimed_telemetry.hpp"

#include <string>

#include "geo/wgs84.hpp"
#include "state/precision.hpp"

namespace gimbal::session {

using state::angle_deg;
using state::latlon_deg;
using state::metres;

std::optional<geo::GroundPoint> fill_from_aircraft(state::Telemetry& t,
                                                   const vehicle::AircraftFix& aircraft,
                                                   double geoid_undulation_m,
                                                   const geo::CameraPose& camera,
                                                   const geo::Ground& ground) {
    t.lat = latlon_deg(camera.position.lat_deg);
    t.lon = latlon_deg(camera.position.lon_deg);
    t.alt = metres(camera.position.alt_m);
    t.alt_msl = metres(aircraft.alt_msl_m);
    t.geoid_undulation = metres(geoid_undulation_m);
    t.roll = angle_deg(aircraft.roll_deg);
    t.pitch = angle_deg(aircraft.pitch_deg);
    t.yaw = angle_deg(aircraft.yaw_deg);
    const auto centre = geo::locate_ground(camera, {0, 0}, ground);
    if (centre)
        t.target = state::GeoPoint{latlon_deg(centre->point.lat_deg),
                                   latlon_deg(centre->point.lon_deg), metres(centre->point.alt_m)};
    t.view = state::ground_view(camera, ground);
    return centre;
}

View view_from(const state::Telemetry* t) {
    View v;
    if (!t) return v;
    v.lat_deg = t->lat;
    v.lon_deg = t->lon;
    v.alt_msl_m = t->alt_msl;
    v.alt_m = t->alt;
    if (t->target) {
        v.target_lat_deg = t->target->lat;
        v.target_lon_deg = t->target->lon;
        if (t->geoid_undulation)
            v.target_alt_msl_m = geo::msl_from_ellipsoid(t->target->alt, *t->geoid_undulation);
    }
    v.hfov_deg = t->hfov;
    v.vfov_deg = t->vfov;
    return v;
}

command::Result<ImageView> image_from(const state::Telemetry* t,
                                      const std::optional<geo::Quat>& line_of_sight,
                                      std::string_view who) {
    if (!t || !t->lat || !t->lon || !t->alt || !t->hfov || !t->vfov || !line_of_sight)
        return command::Error{command::code::unavailable,
                              "no " + std::string(who) + " attitude with a vehicle position yet"};
    ImageView v;
    v.camera = geo::CameraPose{{*t->lat, *t->lon, *t->alt}, *line_of_sight, *t->hfov, *t->vfov};
    if (t->target) v.flat_alt_m = t->target->alt;
    v.geoid_undulation_m = t->geoid_undulation;
    return v;
}

std::optional<geo::Quat> aircraft_attitude_from(const state::Telemetry* t) {
    if (!t || !t->roll || !t->pitch || !t->yaw) return std::nullopt;
    return geo::euler_to_quat(geo::EulerDeg{*t->roll, *t->pitch, *t->yaw});
}

}  // namespace gimbal::session
