// gimbal-export's view of a MAVLink gimbal device recording: one track point per
// GIMBAL_DEVICE_ATTITUDE_STATUS, with the device's angles. The device link carries no
// position (the aircraft's comes from the vehicle feed), so the points have no aircraft,
// target or footprint.
#pragma once

#include <memory>

#include "protocols/track.hpp"

namespace gimbal::protocols {

std::unique_ptr<TrackDecoder> make_mavlink_device_track_decoder();

}  // namespace gimbal::protocols
