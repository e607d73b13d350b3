#include "sim/frames.hpp"

#include <GeographicLib/Constants.hpp>
#include <algorithm>

#include "geo/wgs84.hpp"

namespace gimbal::sim {

double angle_between(Vec3 a, Vec3 b) {
    const double na = norm(a);
    const double nb = norm(b);
    if (na == 0 || nb == 0) return 0;
    // atan2 of |a x b| and a.b stays accurate for tiny angles, unlike acos.
    return std::atan2(norm(cross(a, b)), dot(a, b));
}

Vec3 operator*(const Mat3& r, Vec3 v) {
    const auto& m = r.m;
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Mat3 transpose(const Mat3& r) {
    Mat3 t;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) t.m[i][j] = r.m[j][i];
    return t;
}

Mat3 operator*(const Mat3& a, const Mat3& b) {
    Mat3 p;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) {
            double s = 0;
            for (std::size_t k = 0; k < 3; ++k) s += a.m[i][k] * b.m[k][j];
            p.m[i][j] = s;
        }
    return p;
}

Quat quat_from_euler(double roll, double pitch, double yaw) {
    return geo::euler_to_quat(geo::EulerRad{roll, pitch, yaw});
}

Mat3 dcm_from_quat(const Quat& q_in) {
    const Quat q = geo::normalized(q_in);
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    Mat3 r;
    r.m = {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
    return r;
}

Vec3 to_ecef(const Lla& p) {
    return geo::lla_to_ecef({p.lat / deg, p.lon / deg, p.alt});
}

Lla to_lla(Vec3 ecef) {
    const geo::Lla g = geo::ecef_to_lla(ecef);
    return {g.lat_deg * deg, g.lon_deg * deg, g.alt_m};
}

Mat3 ned_to_ecef(double lat, double lon) {
    const double sl = std::sin(lat), cl = std::cos(lat);
    const double so = std::sin(lon), co = std::cos(lon);
    Mat3 r;  // columns: north, east, down in ECEF
    r.m = {{{-sl * co, -so, -cl * co}, {-sl * so, co, -cl * so}, {cl, 0, -sl}}};
    return r;
}

std::optional<Vec3> hit_flat_terrain(Vec3 origin, Vec3 dir, double terrain_alt) {
    dir = normalized(dir);
    if (norm(dir) == 0) return std::nullopt;
    if (to_lla(origin).alt <= terrain_alt) return std::nullopt;

    // The surface of constant height is very nearly the ellipsoid with both semi-axes grown by
    // that height: intersect that first, then correct the range with the true geodetic height.
    const double a = GeographicLib::Constants::WGS84_a() + terrain_alt;
    const double b = a - GeographicLib::Constants::WGS84_a() * GeographicLib::Constants::WGS84_f();
    const double ia = 1 / (a * a), ib = 1 / (b * b);
    const double qa = (dir.x * dir.x + dir.y * dir.y) * ia + dir.z * dir.z * ib;
    const double qb = 2 * ((origin.x * dir.x + origin.y * dir.y) * ia + origin.z * dir.z * ib);
    const double qc =
        (origin.x * origin.x + origin.y * origin.y) * ia + origin.z * origin.z * ib - 1;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc < 0) return std::nullopt;
    double s = (-qb - std::sqrt(disc)) / (2 * qa);
    if (s <= 0) return std::nullopt;

    for (int i = 0; i < 3; ++i) {  // Newton steps on height(s) - terrain_alt
        const Vec3 p = origin + s * dir;
        const Lla g = to_lla(p);
        const Vec3 up = -1.0 * (ned_to_ecef(g.lat, g.lon) * Vec3{0, 0, 1});
        const double rate = dot(dir, up);  // metres of height per metre along the ray
        if (rate >= -1e-9) break;
        s -= (g.alt - terrain_alt) / rate;
    }
    return origin + std::max(s, 0.0) * dir;
}

double wrap_pi(double a) {
    a = std::fmod(a + pi, 2 * pi);
    if (a < 0) a += 2 * pi;
    return a - pi;
}

}  // namespace gimbal::sim
