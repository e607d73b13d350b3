// The KLV a simulated camera sends with its video, as a real Orion with KLV on does: MISB ST
// 0601 from the model's own view (sim::CameraView) - platform attitude, sensor position and
// angles, fields of view - with the frame centre, slant range and image corners where the
// rays meet the simulator's analytic terrain (TerrainRayCaster), the ground the picture shows.
// Pure: the caller gives the time stamp.
#pragma once

#include <cstdint>

#include "klv/sensor_set.hpp"
#include "sim/camera_view.hpp"

namespace gimbal::sim_video {

klv::SensorFrame sensor_frame(const sim::CameraView& view, std::uint64_t unix_us);

}  // namespace gimbal::sim_video
