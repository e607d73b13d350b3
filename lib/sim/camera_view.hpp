// What a simulated gimbal's camera sees, in terms every model can give: the camera's pinhole
// pose, the platform it rides on, and how the model's telemetry turns heights into MSL. The
// simulator hook of a protocol that has a camera (protocols/simulator.hpp `camera`) returns
// it, so the rendered video and its KLV (lib/sim_video) never name a protocol.
#pragma once

#include "geo/footprint.hpp"

namespace gimbal::sim {

struct CameraView {
    double model_time_s = 0;        // the model's time the view is of
    geo::CameraPose pose;           // position (WGS84), camera -> NED, fields of view
    geo::Quat platform_to_ned;      // the aircraft (or gimbal mount) the camera rides on
    double geoid_undulation_m = 0;  // the model's geoid height: MSL = WGS84 height - this
    bool monochrome = false;        // an infrared camera: no colour
};

}  // namespace gimbal::sim
