// Fields of view of the gimbal's cameras: the narrowest focal length times the zoom ratio,
// capped at the longest focal length (no digital zoom beyond it), over the focal plane size.
#pragma once

#include "protocols/orion/codec/packets_config.hpp"

namespace gimbal::sim {

struct FieldOfView {
    double horizontal = 0;  // rad
    double vertical = 0;    // rad
};

FieldOfView field_of_view(const orion::CameraSettings& camera, double zoom);

}  // namespace gimbal::sim
