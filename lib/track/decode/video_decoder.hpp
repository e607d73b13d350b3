// H.264 / H.265 access units -> pictures for the tracker (contract section 20: decoding only
// while a track runs, frames scaled to `tracking.width`): FFmpeg's libavcodec, one thread, no
// frame reordering delay beyond the stream's own, then libswscale to BGR at the requested
// width (the aspect kept, the height even; never enlarged). Hostile input is expected: a
// picture larger than max_pixels is refused by the decoder, errors are counted and decoding
// resumes at the next key frame, a picture flagged corrupt is dropped. Nothing here reads a
// clock or does I/O.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

#include "track/wire/messages.hpp"

namespace gimbal::track {

struct DecodedFrame {
    cv::Mat bgr;               // scaled, 8-bit BGR
    std::int64_t pts_90k = 0;  // its access unit's
    int source_width = 0;      // as decoded
    int source_height = 0;
};

struct DecoderStats {
    std::uint64_t units = 0;        // access units given
    std::uint64_t frames = 0;       // pictures out
    std::uint64_t errors = 0;       // units or pictures the decoder refused
    std::uint64_t corrupt = 0;      // pictures flagged corrupt and dropped
    std::uint64_t waiting_key = 0;  // units skipped while waiting for a key frame
};

class VideoDecoder {
  public:
    // Pictures above this many pixels are refused (4096 x 2304).
    static constexpr std::int64_t max_pixels = 4096LL * 2304;

    struct Opened {
        std::unique_ptr<VideoDecoder> decoder;
        std::string error;
    };
    static Opened open(wire::Codec codec, int width);
    ~VideoDecoder();
    VideoDecoder(const VideoDecoder&) = delete;
    VideoDecoder& operator=(const VideoDecoder&) = delete;

    // Decodes one access unit (Annex B) shown at pts_90k and appends the pictures it
    // completes. Until the first key frame, and after an error until the next, units are
    // skipped. False when the decoder refused the unit (counted; decoding goes on).
    bool decode(std::span<const std::uint8_t> annex_b, std::int64_t pts_90k, bool key,
                std::vector<DecodedFrame>& out);

    wire::Codec codec() const;
    int width() const;
    const DecoderStats& stats() const;
    const std::string& last_error() const;

  private:
    struct Impl;
    explicit VideoDecoder(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// The size a source_width x source_height picture is scaled to for `width`: the aspect kept,
// both even, never larger than the source.
cv::Size scaled_size(int source_width, int source_height, int width);

}  // namespace gimbal::track
