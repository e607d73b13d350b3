// The simulated Orion's camera as its video renderer needs it: the same platform, axes and
// fields of view its GeolocateTelemetry reports.
#include "protocols/orion/sim/camera.hpp"
#include "protocols/orion/sim/orion_sim_model.hpp"

namespace gimbal::sim {

OrionCameraView OrionSim::camera_view() const {
    OrionCameraView v;
    v.model_time_s = t_;
    v.position = {platform_.lla.lat / deg, platform_.lla.lon / deg, platform_.lla.alt};
    v.mount_to_ned = platform_.attitude;
    v.pan_rad = axes_.angles().pan;
    v.tilt_rad = axes_.angles().tilt;
    const auto& camera = cameras_.cameras[active_camera_];
    const FieldOfView fov = field_of_view(camera, zoom_[active_camera_]);
    v.hfov_rad = fov.horizontal;
    v.vfov_rad = fov.vertical;
    v.geoid_undulation_m = options_.geoid_undulation_m;
    v.infrared = camera.type == orion::CameraType::swir || camera.type == orion::CameraType::mwir ||
                 camera.type == orion::CameraType::lwir;
    return v;
}

std::optional<OrionCameraView> orion_sim_camera(const Device& device) {
    const auto* orion = dynamic_cast<const OrionSim*>(&device);
    if (!orion) return std::nullopt;
    return orion->camera_view();
}

}  // namespace gimbal::sim
