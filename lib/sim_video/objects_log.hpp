// gimbal-sim --objects-log: the moving objects' truth, one JSON object per line per object per
// frame (contract section 20, "Simulator"; fields in docs/simulator.md "Moving objects").
// Pure: the caller writes the text.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "sim_video/object_truth.hpp"

namespace gimbal::sim_video {

struct FrameStamp {
    std::uint64_t frame = 0;    // counted from 0 by the sender
    std::uint64_t unix_us = 0;  // when it was taken (its time code, its KLV time stamp)
    std::int64_t pts_90k = 0;   // its presentation time in the stream
    double model_time_s = 0;    // the model's time the objects are at
};

// The lines for one frame, each ending in '\n'.
std::string objects_log_lines(const FrameStamp& stamp, std::span<const ObjectTruth> objects);

}  // namespace gimbal::sim_video
