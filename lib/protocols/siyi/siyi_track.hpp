// gimbal-export's view of a SIYI recording: one track point per attitude frame (0x0D) with
// the camera's pan and tilt. The camera knows no position of its own: no aircraft or target.
#pragma once

#include <memory>

#include "protocols/track.hpp"

namespace gimbal::protocols {

std::unique_ptr<TrackDecoder> make_siyi_track_decoder();

}  // namespace gimbal::protocols
