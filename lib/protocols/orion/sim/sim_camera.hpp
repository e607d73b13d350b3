// The simulated Orion's camera as a geo::CameraPose, for rendering its video: the pose
// gimbald itself derives from the gimbal's telemetry (position, mount quaternion, pan, tilt,
// fields of view), so a ground point geo::project places in gimbald appears there in the
// picture. Call after the Device's advance(t): the pose is the model's at t.
#pragma once

#include <optional>

#include "geo/footprint.hpp"
#include "protocols/orion/sim/orion_sim.hpp"
#include "sim/camera_view.hpp"
#include "sim/device.hpp"
#include "sim/scene_renderer.hpp"

namespace gimbal::sim {

geo::CameraPose camera_pose(const OrionCameraView& view);

// nullopt when the device is not a simulated Orion.
std::optional<geo::CameraPose> orion_camera_pose(const Device& device);

// The view as every simulated camera gives it (its pose; monochrome when infrared): what the
// simulator hook hands the rendered video and its KLV.
CameraView camera_view(const OrionCameraView& view);

// Scene options for the view's camera: `base` with monochrome set for an infrared camera.
SceneOptions scene_options_for(const OrionCameraView& view, SceneOptions base = {});

}  // namespace gimbal::sim
