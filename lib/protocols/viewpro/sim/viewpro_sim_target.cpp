#include "protocols/viewpro/sim/viewpro_sim_target.hpp"

#include <cmath>

#include "sim/frames.hpp"
#include "sim/pointing.hpp"

namespace gimbal::sim {

std::optional<ViewproTarget> locate_viewpro_target(const ViewproPose& pose, const ViewproLook& look,
                                                   double terrain_alt_msl_m,
                                                   double geoid_undulation_m,
                                                   std::optional<double> range_m) {
    const double lat = pose.lat_deg * deg, lon = pose.lon_deg * deg;
    const Quat body_to_ned =
        quat_from_euler(pose.roll_deg * deg, pose.pitch_deg * deg, pose.yaw_deg * deg);
    const Vec3 dir = mount_to_ecef(body_to_ned, lat, lon) *
                     los_in_mount(PanTilt{look.yaw_deg * deg, look.pitch_deg * deg});
    const Vec3 origin = to_ecef({lat, lon, pose.alt_msl_m + geoid_undulation_m});

    Vec3 point;
    if (range_m) {
        if (!(*range_m > 0) || !std::isfinite(*range_m)) return std::nullopt;
        point = origin + *range_m * dir;
    } else if (auto hit = hit_flat_terrain(origin, dir, terrain_alt_msl_m + geoid_undulation_m)) {
        point = *hit;
    } else {
        return std::nullopt;
    }
    const Lla p = to_lla(point);
    return ViewproTarget{p.lat / deg, p.lon / deg, p.alt - geoid_undulation_m,
                         norm(point - origin)};
}

}  // namespace gimbal::sim
