#include "geo/ray_path.hpp"

#include <cmath>

namespace gimbal::geo {

namespace {

constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_f = 1 / 298.257223563;
constexpr double wgs84_e2 = wgs84_f * (2 - wgs84_f);

}  // namespace

RayPath::RayPath(const Lla& from, const Vec3& dir_ecef)
    : origin_(lla_to_ecef(from)), dir_((1.0 / norm(dir_ecef)) * dir_ecef), lon_ref_(from.lon_deg) {}

Lla RayPath::exact(double t_m) const {
    return ecef_to_lla(origin_ + t_m * dir_);
}

RayPath::Node RayPath::node(double t_m) const {
    const Lla p = exact(t_m);
    // The rates of latitude and longitude follow from the ray's north and east components
    // and the radii of curvature (meridian M, prime vertical N) at the point.
    const Vec3 ned = ecef_to_ned(dir_, p);
    const double lat = p.lat_deg * deg2rad;
    const double s = std::sin(lat);
    const double w = std::sqrt(1 - wgs84_e2 * s * s);
    const double n_radius = wgs84_a / w;
    const double m_radius = wgs84_a * (1 - wgs84_e2) / (w * w * w);
    double lon = p.lon_deg;
    // Keep longitude continuous from the start (a ray may cross the antimeridian).
    while (lon - lon_ref_ > 180) lon -= 360;
    while (lon - lon_ref_ < -180) lon += 360;
    return {p.lat_deg,
            lon,
            p.alt_m,
            ned.x / (m_radius + p.alt_m) * rad2deg,
            ned.y / ((n_radius + p.alt_m) * std::cos(lat)) * rad2deg,
            -ned.z};
}

RaySample RayPath::at(double t_m) {
    const long seg = static_cast<long>(std::floor(t_m / node_spacing_m));
    if (seg != segment_) {
        a_ = node(static_cast<double>(seg) * node_spacing_m);
        b_ = node(static_cast<double>(seg + 1) * node_spacing_m);
        segment_ = seg;
    }
    // Cubic Hermite on [0, 1] with s = (t - t_a) / L.
    const double len = node_spacing_m;
    const double s = t_m / len - static_cast<double>(seg);
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1;
    const double d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
    const double e00 = 12 * s - 6, e10 = 6 * s - 4, e01 = -12 * s + 6, e11 = 6 * s - 2;
    auto value = [&](double pa, double ma, double pb, double mb) {
        return h00 * pa + h10 * len * ma + h01 * pb + h11 * len * mb;
    };
    auto rate = [&](double pa, double ma, double pb, double mb) {
        return (d00 * pa + d10 * len * ma + d01 * pb + d11 * len * mb) / len;
    };
    RaySample out;
    out.lat_deg = value(a_.lat, a_.dlat, b_.lat, b_.dlat);
    out.lon_deg = value(a_.lon, a_.dlon, b_.lon, b_.dlon);
    out.alt_m = value(a_.alt, a_.dalt, b_.alt, b_.dalt);
    out.dlat = rate(a_.lat, a_.dlat, b_.lat, b_.dlat);
    out.dlon = rate(a_.lon, a_.dlon, b_.lon, b_.dlon);
    out.dalt = rate(a_.alt, a_.dalt, b_.alt, b_.dalt);
    out.d2alt =
        (e00 * a_.alt + e10 * len * a_.dalt + e01 * b_.alt + e11 * len * b_.dalt) / (len * len);
    return out;
}

}  // namespace gimbal::geo
