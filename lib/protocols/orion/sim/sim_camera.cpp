#include "protocols/orion/sim/sim_camera.hpp"

#include "geo/image.hpp"

namespace gimbal::sim {

geo::CameraPose camera_pose(const OrionCameraView& view) {
    // lib/sim's pan/tilt convention (pointing.hpp) is geo::line_of_sight_attitude's.
    return geo::camera_pose(view.position, view.mount_to_ned, view.pan_rad * geo::rad2deg,
                            view.tilt_rad * geo::rad2deg, view.hfov_rad * geo::rad2deg,
                            view.vfov_rad * geo::rad2deg);
}

std::optional<geo::CameraPose> orion_camera_pose(const Device& device) {
    const auto view = orion_sim_camera(device);
    if (!view) return std::nullopt;
    return camera_pose(*view);
}

CameraView camera_view(const OrionCameraView& view) {
    return CameraView{view.model_time_s, camera_pose(view), view.mount_to_ned,
                      view.geoid_undulation_m, view.infrared};
}

SceneOptions scene_options_for(const OrionCameraView& view, SceneOptions base) {
    base.monochrome = view.infrared;
    return base;
}

}  // namespace gimbal::sim
