#include "geo/image.hpp"

#include <cmath>

namespace gimbal::geo {

namespace {

bool finite(const Lla& p) {
    return std::isfinite(p.lat_deg) && std::isfinite(p.lon_deg) && std::isfinite(p.alt_m);
}

double half_tan(double fov_deg) {
    return std::tan(fov_deg * deg2rad / 2);
}

}  // namespace

CameraPose camera_pose(const Lla& position, const Quat& mount_to_ned, double pan_deg,
                       double tilt_deg, double hfov_deg, double vfov_deg,
                       double image_rotation_deg) {
    Quat q = line_of_sight_attitude(mount_to_ned, pan_deg, tilt_deg);
    if (image_rotation_deg != 0)
        q = normalized(q * euler_to_quat(EulerDeg{image_rotation_deg, 0, 0}));
    return {position, q, hfov_deg, vfov_deg};
}

bool valid(const CameraPose& c) {
    const Quat& q = c.camera_to_ned;
    return finite(c.position) && std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) &&
           std::isfinite(q.z) && (q.w != 0 || q.x != 0 || q.y != 0 || q.z != 0) && c.hfov_deg > 0 &&
           c.hfov_deg < 180 && c.vfov_deg > 0 && c.vfov_deg < 180;
}

Vec3 image_ray_camera(const CameraPose& c, ImagePoint p) {
    return {1, p.x * half_tan(c.hfov_deg), p.y * half_tan(c.vfov_deg)};
}

Vec3 image_ray_ned(const CameraPose& c, ImagePoint p) {
    return rotate(c.camera_to_ned, image_ray_camera(c, p));
}

Vec3 image_ray_ecef(const CameraPose& c, ImagePoint p) {
    return ned_to_ecef(image_ray_ned(c, p), c.position);
}

std::optional<ImagePoint> from_pixels(PixelPoint p, double width, double height) {
    if (!(width > 0) || !(height > 0) || !std::isfinite(width) || !std::isfinite(height) ||
        !std::isfinite(p.px) || !std::isfinite(p.py))
        return std::nullopt;
    return ImagePoint{2 * p.px / width - 1, 2 * p.py / height - 1};
}

std::optional<PixelPoint> to_pixels(ImagePoint p, double width, double height) {
    if (!(width > 0) || !(height > 0) || !std::isfinite(width) || !std::isfinite(height) ||
        !std::isfinite(p.x) || !std::isfinite(p.y))
        return std::nullopt;
    return PixelPoint{(p.x + 1) * width / 2, (p.y + 1) * height / 2};
}

Location locate(const CameraPose& camera, ImagePoint p, Surface& surface,
                const RayOptions& options) {
    if (!valid(camera) || !std::isfinite(p.x) || !std::isfinite(p.y))
        return {{RayStatus::invalid, camera.position, 0}, surface.kind()};
    return {surface.intersect(camera.position, image_ray_ecef(camera, p), options), surface.kind()};
}

std::optional<Projection> project(const CameraPose& camera, const Lla& point, Surface* surface,
                                  double occlusion_tolerance_m) {
    if (!valid(camera) || !finite(point)) return std::nullopt;
    const Vec3 ecef = lla_to_ecef(point) - lla_to_ecef(camera.position);
    const Vec3 cam =
        rotate(conjugate(normalized(camera.camera_to_ned)), ecef_to_ned(ecef, camera.position));
    Projection out;
    if (!(cam.x > 0)) return out;
    out.in_front = true;
    out.at = {cam.y / cam.x / half_tan(camera.hfov_deg), cam.z / cam.x / half_tan(camera.vfov_deg)};
    out.visible = std::abs(out.at.x) <= 1 && std::abs(out.at.y) <= 1;
    if (out.visible && surface) {
        const double distance = norm(ecef);
        const Intersection hit =
            surface->intersect(camera.position, ecef, RayOptions{distance + 1});
        // Hidden when the surface is met well before the point, or the camera is under it.
        if (hit.status == RayStatus::below_surface ||
            (hit.status == RayStatus::hit && hit.range_m < distance - occlusion_tolerance_m))
            out.visible = false;
    }
    return out;
}

std::optional<PanTilt> pan_tilt_towards(const Quat& mount_to_ned, const Lla& from, const Lla& to) {
    if (!finite(from) || !finite(to)) return std::nullopt;
    const Vec3 ned = ecef_to_ned(lla_to_ecef(to) - lla_to_ecef(from), from);
    if (!(norm(ned) > 0)) return std::nullopt;
    const Vec3 m = rotate(conjugate(normalized(mount_to_ned)), ned);
    // line_of_sight_attitude looks along (cos t cos p, cos t sin p, -sin t) in the mount.
    return PanTilt{std::atan2(m.y, m.x) * rad2deg,
                   std::atan2(-m.z, std::hypot(m.x, m.y)) * rad2deg};
}

std::optional<SurfaceFootprint> footprint(const CameraPose& camera, Surface& surface,
                                          const RayOptions& options, RayStatus* first_failure) {
    static constexpr std::array<ImagePoint, 4> corners{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
    SurfaceFootprint out;
    out.surface = surface.kind();
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Location l = locate(camera, corners[i], surface, options);
        if (l.ray.status != RayStatus::hit) {
            if (first_failure) *first_failure = l.ray.status;
            return std::nullopt;
        }
        out.corners[i] = l.ray.point;
        out.range_m[i] = l.ray.range_m;
    }
    return out;
}

}  // namespace gimbal::geo
