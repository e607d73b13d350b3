#include "sim_video/sim_klv.hpp"

#include <cmath>

#include "sim/terrain_ray.hpp"

namespace gimbal::sim_video {

namespace {

constexpr double deg2rad = 3.14159265358979323846 / 180.0;

}  // namespace

klv::SensorFrame sensor_frame(const sim::CameraView& view, std::uint64_t unix_us) {
    klv::SensorFrame f;
    f.time_us = unix_us;
    const geo::CameraPose& pose = view.pose;
    const double n = view.geoid_undulation_m;
    f.sensor_lat_deg = pose.position.lat_deg;
    f.sensor_lon_deg = pose.position.lon_deg;
    f.sensor_alt_msl_m = pose.position.alt_m - n;
    f.hfov_deg = pose.hfov_deg;
    f.vfov_deg = pose.vfov_deg;

    const geo::EulerDeg platform = geo::quat_to_euler(view.platform_to_ned);
    f.platform_heading_deg = platform.yaw_deg;
    f.platform_pitch_deg = platform.pitch_deg;
    f.platform_roll_deg = platform.roll_deg;
    const geo::EulerDeg relative = geo::quat_to_euler(
        geo::normalized(geo::conjugate(view.platform_to_ned) * pose.camera_to_ned));
    f.relative_azimuth_deg = relative.yaw_deg;
    f.relative_elevation_deg = relative.pitch_deg;
    f.relative_roll_deg = relative.roll_deg;

    // Camera frame: x along the line of sight, y to the image's right, z down the image.
    const sim::TerrainRayCaster caster(pose.position);
    const auto cast = [&](double x, double y) {
        const geo::Vec3 in_camera{1.0, x * std::tan(pose.hfov_deg * deg2rad / 2),
                                  y * std::tan(pose.vfov_deg * deg2rad / 2)};
        return caster.cast(geo::rotate(pose.camera_to_ned, in_camera));
    };
    const auto centre = cast(0, 0);
    if (centre.status != sim::TerrainRayCaster::Status::hit) return f;
    f.frame_center =
        klv::GroundPoint{centre.point.lat_deg, centre.point.lon_deg, centre.point.alt_m - n};
    f.slant_range_m = centre.range_m;  // calculated, not measured
    std::array<klv::LatLon, 4> corners{};
    constexpr double xs[] = {-1, 1, 1, -1};  // upper left, upper right, lower right, lower left
    constexpr double ys[] = {-1, -1, 1, 1};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto hit = cast(xs[i], ys[i]);
        if (hit.status != sim::TerrainRayCaster::Status::hit) return f;
        corners[i] = {hit.point.lat_deg, hit.point.lon_deg};
    }
    f.corners = corners;
    return f;
}

}  // namespace gimbal::sim_video
