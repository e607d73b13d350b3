// The simulated camera's video, frame by frame: render the scene the camera sees
// (sim::SceneRenderer), draw the frame's time into it (sim/frame_code.hpp), encode it
// (H264Encoder). The caller owns time: it says when each frame is taken (Unix ms, drawn as the
// time code) and its presentation time (90 kHz, as MPEG-TS counts). Muxing and sending are
// the caller's (lib/video, daemon).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geo/footprint.hpp"
#include "sim/camera_view.hpp"
#include "sim/i420_frame.hpp"
#include "sim/scene_renderer.hpp"
#include "sim_video/h264_encoder.hpp"
#include "sim_video/object_truth.hpp"

namespace gimbal::sim_video {

struct SimVideoOptions {
    // The picture: width, height, ray grid. The encoder's size follows it.
    sim::SceneOptions scene;
    H264Options h264;
    // The moving objects drawn on the ground (at each view's model time): none by default.
    sim::ObjectSet objects;
};

class SimVideoSource {
  public:
    // The source, or why not (bad_request for options, unavailable for the encoder).
    static Result<std::unique_ptr<SimVideoSource>> open(const SimVideoOptions& options);

    // One frame of what `camera` sees (the still scene: no moving objects), taken at unix_ms
    // and shown at pts_90k; its access unit(s) are appended to `out`. False (error() says why)
    // when the encoder refuses it; an invalid camera still gives a (grey) frame.
    bool frame(const geo::CameraPose& camera, std::uint64_t unix_ms, std::int64_t pts_90k,
               std::vector<AccessUnit>& out);
    // Any simulated camera (a protocol's simulator hook): its pose, grey when monochrome, and
    // the options' moving objects where they are at the view's model time.
    bool frame(const sim::CameraView& view, std::uint64_t unix_ms, std::int64_t pts_90k,
               std::vector<AccessUnit>& out);

    // The moving objects of the last frame, as the camera saw them.
    const std::vector<ObjectTruth>& objects() const { return truth_; }

    // The last frame as rendered (time code included), before encoding.
    const sim::I420Frame& picture() const { return picture_; }
    const sim::RenderStats& render_stats() const { return renderer_.stats(); }
    const H264Encoder& encoder() const { return *encoder_; }
    const std::string& error() const { return encoder_->error(); }

  private:
    SimVideoSource(const SimVideoOptions& options, std::unique_ptr<H264Encoder> encoder);
    bool encode(std::uint64_t unix_ms, std::int64_t pts_90k, std::vector<AccessUnit>& out);

    sim::ObjectSet object_set_;
    std::vector<ObjectTruth> truth_;
    sim::SceneRenderer renderer_;
    std::unique_ptr<H264Encoder> encoder_;
    sim::I420Frame picture_;
};

}  // namespace gimbal::sim_video
