// The simulated SIYI camera's view, for the rendered video and its KLV (the simulator hook's
// `camera`): the pose gimbald itself derives from the camera's attitude and the vehicle feed
// (protocols/siyi/siyi_state.cpp), so a point gimbald aims at appears at the picture's centre
// and a click in the picture lands where the model looks. Call after the Device's advance(t).
#pragma once

#include <optional>

#include "protocols/siyi/sim/siyi_sim.hpp"
#include "sim/camera_view.hpp"
#include "sim/device.hpp"

namespace gimbal::protocols {

// The main (zoom) camera of `sim`: at the aircraft's position, its pitch and roll stabilized
// (earth frame), its yaw from the aircraft's nose, the model's fields of view at the zoom.
sim::CameraView siyi_camera_view(const SiyiSim& sim);

// nullopt when the device is not a simulated SIYI camera.
std::optional<sim::CameraView> siyi_sim_camera(const sim::Device& device);

}  // namespace gimbal::protocols
