// A picture in planar YUV 4:2:0 (I420): full-resolution luma, chroma at half resolution in
// both directions, each plane stored row after row without padding. The simulated camera
// renders into it and the H.264 encoder reads it. Colours are BT.601 limited range ("studio
// swing": Y 16..235, U and V 16..240 around 128), as the encoder signals them.
#pragma once

#include <cstdint>
#include <vector>

namespace gimbal::sim {

struct I420Frame {
    int width = 0;                // pixels, even
    int height = 0;               // pixels, even
    std::vector<std::uint8_t> y;  // width x height
    std::vector<std::uint8_t> u;  // width/2 x height/2
    std::vector<std::uint8_t> v;  // width/2 x height/2

    int chroma_width() const { return width / 2; }
    int chroma_height() const { return height / 2; }
    // Sizes the planes (contents unspecified). False, and nothing changes, unless width and
    // height are even and in 2..16384.
    bool resize(int new_width, int new_height);
    std::uint8_t luma(int px, int py) const;
    // The chroma sample covering pixel (px, py).
    std::uint8_t cb(int px, int py) const;
    std::uint8_t cr(int px, int py) const;
};

struct Rgb {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;
};

struct Yuv {
    std::uint8_t y = 16;
    std::uint8_t u = 128;
    std::uint8_t v = 128;
};

// BT.601 limited range, rounded.
Yuv to_yuv(Rgb c);

}  // namespace gimbal::sim
