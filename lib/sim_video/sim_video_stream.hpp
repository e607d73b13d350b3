// The simulated camera's stream as a real Orion sends it (contract section 17: "h.264+KLV in
// an MPEG transport stream"): each frame rendered and encoded (SimVideoSource), muxed into
// MPEG-TS by lib/video's TsMuxer together with a MISB ST 0601 set for the same moment
// (sim_klv.hpp) on the asynchronous KLV stream, with the frame's PTS. Datagram-sized chunks
// (7 TS packets) go to the sink. Pure apart from the encoder: the caller gives each frame's
// time and PTS, and sends the chunks.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sim/camera_view.hpp"
#include "sim_video/sim_video_source.hpp"
#include "video/ts_muxer.hpp"

namespace gimbal::sim_video {

struct SimVideoStreamOptions {
    SimVideoOptions video;  // size, frame rate, bit rate
    bool klv = true;        // a KLV set with every frame (an Orion with KLV off: false)
    video::MuxerOptions mux;
};

struct SimVideoStreamStats {
    std::uint64_t frames = 0;
    std::uint64_t key_frames = 0;
    std::uint64_t klv_sets = 0;
    std::uint64_t bytes = 0;  // TS bytes handed to the sink
};

class SimVideoStream {
  public:
    using Sink = std::function<void(std::span<const std::uint8_t> chunk)>;
    static Result<std::unique_ptr<SimVideoStream>> open(const SimVideoStreamOptions& options,
                                                        Sink sink);

    // One frame of `view`, taken at unix_us (drawn as the time code, and the KLV's time
    // stamp) and shown at pts_90k (increasing). False with error() when the encoder fails.
    bool frame(const sim::CameraView& view, std::uint64_t unix_us, std::int64_t pts_90k);

    const SimVideoStreamStats& stats() const { return stats_; }
    const SimVideoSource& source() const { return *source_; }
    const std::string& error() const { return error_; }

  private:
    SimVideoStream(const SimVideoStreamOptions& options, std::unique_ptr<SimVideoSource> source,
                   Sink sink);

    bool klv_;
    std::unique_ptr<SimVideoSource> source_;
    Sink sink_;
    video::TsMuxer mux_;
    std::vector<AccessUnit> units_;
    SimVideoStreamStats stats_;
    std::string error_;
};

}  // namespace gimbal::sim_video
