// gimbal-export's view of a Viewpro recording: one track point per OUT1..OUT4 frame; pan and
// tilt are the gimbal's yaw and pitch, positions are MSL, and there is no footprint (no field
// of view in the frames).
#pragma once

#include <memory>

#include "protocols/track.hpp"

namespace gimbal::protocols {

std::unique_ptr<TrackDecoder> make_viewpro_track_decoder();

// One decoded OUTx (viewpro::to_json) -> a track point.
TrackPoint viewpro_track_point(std::int64_t time_us, const nlohmann::json& output);

}  // namespace gimbal::protocols
