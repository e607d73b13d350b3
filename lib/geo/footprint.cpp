#include "geo/footprint.hpp"

#include <cmath>

namespace gimbal::geo {

namespace {

// WGS84 semi-axes (m).
constexpr double wgs84_a = 6378137.0;
constexpr double wgs84_b = 6356752.314245179;

bool finite(const Lla& p) {
    return std::isfinite(p.lat_deg) && std::isfinite(p.lon_deg) && std::isfinite(p.alt_m);
}

// The smallest positive t with (P + tD) on the ellipsoid of semi-axes (a, a, b), if any.
std::optional<double> first_hit(const Vec3& p, const Vec3& d, double a, double b) {
    // Scale z so the ellipsoid becomes a sphere of radius a.
    const double k = a / b;
    const Vec3 ps{p.x, p.y, p.z * k};
    const Vec3 ds{d.x, d.y, d.z * k};
    const double qa = dot(ds, ds);
    const double qb = 2 * dot(ps, ds);
    const double qc = dot(ps, ps) - a * a;
    const double disc = qb * qb - 4 * qa * qc;
    if (qa <= 0 || disc < 0) return std::nullopt;
    const double root = std::sqrt(disc);
    const double near = (-qb - root) / (2 * qa);
    const double far = (-qb + root) / (2 * qa);
    if (near > 0) return near;
    if (far > 0) return far;
    return std::nullopt;
}

}  // namespace

Quat line_of_sight_attitude(const Quat& mount_to_ned, double pan_deg, double tilt_deg) {
    return normalized(normalized(mount_to_ned) * euler_to_quat(EulerDeg{0, tilt_deg, pan_deg}));
}

std::optional<Lla> ray_to_surface(const Lla& from, const Vec3& dir_ecef, double surface_alt_m) {
    if (!finite(from) || !std::isfinite(surface_alt_m) || !std::isfinite(norm(dir_ecef)) ||
        norm(dir_ecef) == 0)
        return std::nullopt;
    if (from.alt_m <= surface_alt_m) return std::nullopt;
    const Vec3 p = lla_to_ecef(from);
    const Vec3 d = (1.0 / norm(dir_ecef)) * dir_ecef;
    // The ellipsoid with both semi-axes lengthened by h is close to, not exactly, the surface
    // h above the ellipsoid: start there, then step along the ray until the geodetic
    // altitude is right (Newton on alt(t) - h; d alt / dt is the ray's upward component).
    auto t = first_hit(p, d, wgs84_a + surface_alt_m, wgs84_b + surface_alt_m);
    if (!t) return std::nullopt;
    for (int i = 0; i < 4; ++i) {
        const Lla at = ecef_to_lla(p + *t * d);
        const double error_m = at.alt_m - surface_alt_m;
        const double climb = dot(d, ned_to_ecef({0, 0, -1}, at));
        if (std::abs(error_m) < 1e-4 || std::abs(climb) < 1e-6) break;
        *t -= error_m / climb;
    }
    if (!(*t > 0)) return std::nullopt;
    return ecef_to_lla(p + *t * d);
}

std::optional<Footprint> footprint(const CameraPose& camera, double ground_alt_m) {
    const auto& q = camera.camera_to_ned;
    if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        return std::nullopt;
    if (!(camera.hfov_deg > 0 && camera.hfov_deg < 180 && camera.vfov_deg > 0 &&
          camera.vfov_deg < 180))
        return std::nullopt;
    const double right = std::tan(camera.hfov_deg * deg2rad / 2);
    const double down = std::tan(camera.vfov_deg * deg2rad / 2);
    // Image corners in the camera frame, in the contract's order.
    const std::array<Vec3, 4> corners{{
        {1, -right, -down},  // top-left
        {1, right, -down},   // top-right
        {1, right, down},    // bottom-right
        {1, -right, down},   // bottom-left
    }};
    Footprint out;
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec3 dir_ned = rotate(q, corners[i]);
        const auto hit =
            ray_to_surface(camera.position, ned_to_ecef(dir_ned, camera.position), ground_alt_m);
        if (!hit) return std::nullopt;
        out[i] = {hit->lat_deg, hit->lon_deg};
    }
    return out;
}

}  // namespace gimbal::geo
