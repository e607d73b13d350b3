// A gimbal's `track`, `track_stop` and STATE `track` (contract section 20), put on its
// session: answered by a TrackController (and its gimbal-track) when the gimbal has video
// with `tracking`; otherwise `track` is `unavailable` (nothing sent, nothing started),
// `track_stop` has nothing to stop and STATE `track` is null.
#pragma once

#include <memory>
#include <optional>

#include <boost/asio/io_context.hpp>

#include "gimbal_session.hpp"
#include "terrain/elevation_model.hpp"
#include "track/track_controller.hpp"
#include "video/gimbal_video.hpp"
#include "video/video_config.hpp"

namespace gimbald::track {

// The controller (not started), or null when the gimbal has no tracking. `video` is the
// gimbal's video (null without one).
std::unique_ptr<TrackController> attach_tracking(boost::asio::io_context& io,
                                                 GimbalSession& session, video::GimbalVideo* video,
                                                 const std::optional<video::VideoConfig>& config,
                                                 gimbal::terrain::ElevationModel* terrain,
                                                 TrackController::EventSink on_event);

}  // namespace gimbald::track
