#include "geo/ground.hpp"

namespace gimbal::geo {

std::optional<GroundPoint> locate_ground(const CameraPose& camera, ImagePoint p,
                                         const Ground& ground, RayStatus* why) {
    RayStatus status = RayStatus::unknown;  // no surface to meet
    if (ground.terrain) {
        const Location l = locate(camera, p, *ground.terrain);
        if (l.ray.status == RayStatus::hit)
            return GroundPoint{l.ray.point, l.ray.range_m, SurfaceKind::terrain};
        status = l.ray.status;
        if (status == RayStatus::invalid) {
            if (why) *why = status;
            return std::nullopt;
        }
    }
    if (ground.flat_alt_m) {
        EllipsoidSurface flat(*ground.flat_alt_m);
        const Location l = locate(camera, p, flat);
        if (l.ray.status == RayStatus::hit)
            return GroundPoint{l.ray.point, l.ray.range_m, SurfaceKind::ellipsoid};
        status = l.ray.status;
    }
    if (why) *why = status;
    return std::nullopt;
}

std::optional<SurfaceFootprint> ground_footprint(const CameraPose& camera, const Ground& ground) {
    if (ground.terrain)
        if (auto f = footprint(camera, *ground.terrain)) return f;
    if (!ground.flat_alt_m) return std::nullopt;
    EllipsoidSurface flat(*ground.flat_alt_m);
    return footprint(camera, flat);
}

}  // namespace gimbal::geo
