#include "geo/surface.hpp"

#include <cmath>

#include "geo/footprint.hpp"
#include "geo/ray_march.hpp"

namespace gimbal::geo {

std::string_view to_string(SurfaceKind kind) {
    switch (kind) {
        case SurfaceKind::terrain:
            return "terrain";
        case SurfaceKind::ellipsoid:
            return "ellipsoid";
    }
    return "unknown";
}

std::string_view to_string(RayStatus status) {
    switch (status) {
        case RayStatus::hit:
            return "hit";
        case RayStatus::unknown:
            return "unknown";
        case RayStatus::no_ground:
            return "no_ground";
        case RayStatus::below_surface:
            return "below_surface";
        case RayStatus::invalid:
            return "invalid";
    }
    return "unknown";
}

double wrap_lon(double lon_deg) {
    if (lon_deg >= -180 && lon_deg < 180) return lon_deg;
    const double w = std::fmod(lon_deg + 180, 360);
    return (w < 0 ? w + 360 : w) - 180;
}

double Patch::at(double lat_deg, double lon_deg) const {
    const double u = (lat_deg - lat0) / dlat;
    const double v = (lon_near(lon_deg, lon0 + dlon / 2) - lon0) / dlon;
    return h_sw * (1 - u) * (1 - v) + h_se * (1 - u) * v + h_nw * u * (1 - v) + h_ne * u * v;
}

std::optional<Bound> Surface::bound(double, double, double, double, double) {
    return std::nullopt;
}

Intersection Surface::intersect(const Lla& from, const Vec3& dir_ecef, const RayOptions& options) {
    return march(*this, from, dir_ecef, options);
}

std::optional<Patch> EllipsoidSurface::patch(double, double, double, double) {
    return Patch{{-90, 90, -180, 180}, -90, -180, 180, 360, alt_m_, alt_m_, alt_m_, alt_m_};
}

Intersection EllipsoidSurface::intersect(const Lla& from, const Vec3& dir_ecef, const RayOptions&) {
    if (!std::isfinite(from.lat_deg) || !std::isfinite(from.lon_deg) ||
        !std::isfinite(from.alt_m) || !std::isfinite(norm(dir_ecef)) || norm(dir_ecef) == 0 ||
        !std::isfinite(alt_m_))
        return {RayStatus::invalid, from, 0};
    if (from.alt_m <= alt_m_) return {RayStatus::below_surface, from, 0};
    const auto hit = ray_to_surface(from, dir_ecef, alt_m_);
    if (!hit) return {RayStatus::no_ground, from, 0};
    return {RayStatus::hit, *hit, norm(lla_to_ecef(*hit) - lla_to_ecef(from))};
}

}  // namespace gimbal::geo
