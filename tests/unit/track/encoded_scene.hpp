// The synthetic scene as the tracker's process receives it: each frame converted to I420 and
// encoded by lib/sim_video's H.264 encoder (libavcodec, libx264: constrained baseline, an IDR
// with SPS and PPS every second), one Annex B access unit per frame with its 90 kHz time.
#pragma once

#include <cstring>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "sim/i420_frame.hpp"
#include "sim_video/h264_encoder.hpp"
#include "synthetic_scene.hpp"

namespace track_test {

inline gimbal::sim::I420Frame to_i420(const cv::Mat& bgr) {
    cv::Mat yuv;
    cv::cvtColor(bgr, yuv, cv::COLOR_BGR2YUV_I420);  // Y plane, then U, then V
    gimbal::sim::I420Frame f;
    f.resize(bgr.cols, bgr.rows);
    const auto* p = yuv.ptr<std::uint8_t>();
    std::memcpy(f.y.data(), p, f.y.size());
    std::memcpy(f.u.data(), p + f.y.size(), f.u.size());
    std::memcpy(f.v.data(), p + f.y.size() + f.u.size(), f.v.size());
    return f;
}

// Frames 0 .. count-1 of `scene` at `fps`, encoded; frame i is shown at t = i / fps.
inline std::vector<gimbal::sim_video::AccessUnit> encode_scene(const SyntheticScene& scene,
                                                               int count, int fps,
                                                               int bitrate_bps = 1200000) {
    gimbal::sim_video::H264Options options;
    options.width = scene.options().width;
    options.height = scene.options().height;
    options.fps = fps;
    options.bitrate_bps = bitrate_bps;
    auto opened = gimbal::sim_video::H264Encoder::open(options);
    if (!opened) throw std::runtime_error(opened.error().message);
    auto& encoder = *opened.value();
    std::vector<gimbal::sim_video::AccessUnit> units;
    for (int i = 0; i < count; ++i) {
        const auto frame = to_i420(scene.render(static_cast<double>(i) / fps));
        if (!encoder.encode(frame, static_cast<std::int64_t>(i) * 90000 / fps, units))
            throw std::runtime_error(encoder.error());
    }
    encoder.flush(units);
    return units;
}

}  // namespace track_test
