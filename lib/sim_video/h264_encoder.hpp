// H.264 encoding of I420 frames through FFmpeg's libavcodec and libx264, set up for live
// low-latency video a browser can decode (docs/simulator.md "Encoder"): constrained baseline
// profile (no B-frames, CAVLC) at level 3.0, tune zerolatency (no lookahead: each frame comes
// out of encode() as its own access unit), an IDR key frame every key_interval_s with SPS and
// PPS in front of it, an access unit delimiter first in every access unit (as MPEG-TS wants),
// bitrate capped by a VBV of half a second, BT.601 limited range signalled in the VUI. Annex
// B byte stream out. No clock reads: the caller gives each frame its time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/i420_frame.hpp"

#include "result/result.hpp"

namespace gimbal::sim_video {

struct H264Options {
    int width = 640;              // even, 16..4096
    int height = 360;             // even, 16..4096
    int fps = 15;                 // nominal frame rate, 1..120 (rate control and the SPS timing)
    int bitrate_bps = 1200000;    // target and cap, 50 kbit/s..50 Mbit/s
    double key_interval_s = 1.0;  // an IDR every round(key_interval_s * fps) frames (>= 1)
    std::string preset = "veryfast";   // x264 preset: ultrafast .. medium
    std::string profile = "baseline";  // x264 profile: baseline (constrained), main, high
    int threads = 1;                   // encoder threads (0: x264 decides)
};
// Empty when valid, else what is wrong.
std::string check(const H264Options& options);

struct AccessUnit {
    std::vector<std::uint8_t> annex_b;  // AUD, [SPS, PPS,] [SEI,] slice(s)
    std::int64_t pts_90k = 0;           // presentation time = decode time (no B-frames)
    bool key = false;                   // an IDR picture (SPS and PPS included)
};

class H264Encoder {
  public:
    // Fails when the options are invalid (bad_request, check()'s message) or this FFmpeg has
    // no libx264 or cannot open it (unavailable).
    static Result<std::unique_ptr<H264Encoder>> open(const H264Options& options);
    ~H264Encoder();
    H264Encoder(const H264Encoder&) = delete;
    H264Encoder& operator=(const H264Encoder&) = delete;

    // Encodes a frame of the options' size shown at pts_90k (90 kHz, increasing) and appends
    // the access units finished meanwhile to `out` (with these settings: this frame's). False
    // (error() says why, nothing appended) for a frame of another size, a time not after the
    // previous one, or an encoder failure.
    bool encode(const sim::I420Frame& frame, std::int64_t pts_90k, std::vector<AccessUnit>& out);
    // Ends the stream: appends whatever the encoder still holds. No encode() after it.
    bool flush(std::vector<AccessUnit>& out);

    const H264Options& options() const;
    int key_interval_frames() const;
    const std::string& error() const;

  private:
    struct Impl;
    explicit H264Encoder(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace gimbal::sim_video
