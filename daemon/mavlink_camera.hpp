// The MAVLink camera components' set-up (contract section 16): each exposed gimbal's camera
// (component 100 + gimbal_device_id - 1), what it can do (the gimbal's capabilities) and the
// streams it announces (the MPEG-TS outputs of its `video` section, section 17).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gimbal_protocol/camera.hpp"
#include "gimbal_session.hpp"
#include "video/video_config.hpp"

namespace gimbald {

// One stream per `udp://` output (klv-udp outputs carry no picture). URI as common.xml gives
// it for VIDEO_STREAM_TYPE_MPEG_TS: the port the ground station listens on; for a multicast
// output `mpegts://GROUP:PORT` (QGroundControl joins the group).
std::vector<gimbal::gimbal_protocol::CameraStream> camera_streams(const std::string& gimbal,
                                                                  const video::VideoConfig& video);

// The camera of every exposed gimbal, in the same order.
std::vector<gimbal::gimbal_protocol::ExposedCamera> expose_cameras(
    const std::vector<gimbal::gimbal_protocol::ExposedGimbal>& gimbals,
    const std::vector<GimbalSession*>& sessions,
    const std::map<std::string, video::VideoConfig>& videos);

}  // namespace gimbald
