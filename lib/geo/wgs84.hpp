// WGS84 geometry: geodetic <-> ECEF (GeographicLib), ECEF vectors <-> local NED, the point a
// line-of-sight vector ends at, look angles between two points, and MSL altitude from the
// geoid undulation. Pure functions of their arguments.
#pragma once

#include <optional>

#include "geo/attitude.hpp"  // telemetry users need attitude and position together
#include "geo/vec3.hpp"

namespace gimbal::geo {

// Geodetic position: degrees (north and east positive), metres above the WGS84 ellipsoid.
struct Lla {
    double lat_deg = 0;
    double lon_deg = 0;
    double alt_m = 0;
};

// Earth-centred, earth-fixed position in metres.
Vec3 lla_to_ecef(const Lla& p);
Lla ecef_to_lla(const Vec3& ecef);

// Rotate a vector (not a position) between ECEF axes and the local North-East-Down axes at p.
// Only the latitude and longitude of p matter.
Vec3 ecef_to_ned(const Vec3& v_ecef, const Lla& at);
Vec3 ned_to_ecef(const Vec3& v_ned, const Lla& at);

// The point at `from` + `los_ecef` (GeolocateTelemetry's losECEF: gimbal -> image location).
// nullopt when the vector is zero (the gimbal sends zeros without ranging data) or not finite.
std::optional<Lla> target_from_los(const Lla& from, const Vec3& los_ecef);

// Where `to` appears from `from`: azimuth clockwise from true north (-180..180], elevation above
// the local horizontal plane (-90..90), straight-line range.
struct LookAngles {
    double azimuth_deg = 0;
    double elevation_deg = 0;
    double range_m = 0;
};
LookAngles look_angles(const Lla& from, const Lla& to);

// Geoid undulation N is the geoid's height above the ellipsoid: h_msl = h_ellipsoid - N.
inline double msl_from_ellipsoid(double alt_ellipsoid_m, double geoid_undulation_m) {
    return alt_ellipsoid_m - geoid_undulation_m;
}
inline double ellipsoid_from_msl(double alt_msl_m, double geoid_undulation_m) {
    return alt_msl_m + geoid_undulation_m;
}

}  // namespace gimbal::geo
