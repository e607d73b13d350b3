#include "protocols/orion/sim/camera.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::sim {

FieldOfView field_of_view(const orion::CameraSettings& camera, double zoom) {
    const double min_f = camera.min_focal_length_mm;
    const double max_f = std::max(camera.max_focal_length_mm, min_f);
    if (min_f <= 0 || camera.pixel_pitch_mm <= 0) return {};
    const double focal = std::clamp(min_f * std::max(zoom, 1.0), min_f, max_f);
    const double width = camera.array_width * camera.pixel_pitch_mm;
    const double height = camera.array_height * camera.pixel_pitch_mm;
    return {2 * std::atan(width / (2 * focal)), 2 * std::atan(height / (2 * focal))};
}

}  // namespace gimbal::sim
