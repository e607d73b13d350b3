#include "geo/wgs84.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <cmath>

namespace gimbal::geo {
namespace {

const GeographicLib::Geocentric& wgs84() {
    return GeographicLib::Geocentric::WGS84();
}

// Unit vectors of the local north, east and down axes, in ECEF.
struct NedAxes {
    Vec3 north, east, down;
};

NedAxes ned_axes(const Lla& at) {
    const double lat = at.lat_deg * deg2rad;
    const double lon = at.lon_deg * deg2rad;
    const double slat = std::sin(lat), clat = std::cos(lat);
    const double slon = std::sin(lon), clon = std::cos(lon);
    return {{-slat * clon, -slat * slon, clat},
            {-slon, clon, 0.0},
            {-clat * clon, -clat * slon, -slat}};
}

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Vec3 lla_to_ecef(const Lla& p) {
    Vec3 out;
    wgs84().Forward(p.lat_deg, p.lon_deg, p.alt_m, out.x, out.y, out.z);
    return out;
}

Lla ecef_to_lla(const Vec3& ecef) {
    Lla out;
    wgs84().Reverse(ecef.x, ecef.y, ecef.z, out.lat_deg, out.lon_deg, out.alt_m);
    return out;
}

Vec3 ecef_to_ned(const Vec3& v, const Lla& at) {
    const NedAxes a = ned_axes(at);
    return {dot(a.north, v), dot(a.east, v), dot(a.down, v)};
}

Vec3 ned_to_ecef(const Vec3& v, const Lla& at) {
    const NedAxes a = ned_axes(at);
    return v.x * a.north + v.y * a.east + v.z * a.down;
}

std::optional<Lla> target_from_los(const Lla& from, const Vec3& los_ecef) {
    if (los_ecef.x == 0 && los_ecef.y == 0 && los_ecef.z == 0) return std::nullopt;
    if (!finite(los_ecef)) return std::nullopt;
    return ecef_to_lla(lla_to_ecef(from) + los_ecef);
}

LookAngles look_angles(const Lla& from, const Lla& to) {
    const Vec3 ned = ecef_to_ned(lla_to_ecef(to) - lla_to_ecef(from), from);
    const double horizontal = std::hypot(ned.x, ned.y);
    LookAngles out;
    out.range_m = norm(ned);
    if (out.range_m == 0) return out;
    out.azimuth_deg = std::atan2(ned.y, ned.x) * rad2deg;
    out.elevation_deg = std::atan2(-ned.z, horizontal) * rad2deg;
    return out;
}

}  // namespace gimbal::geo
