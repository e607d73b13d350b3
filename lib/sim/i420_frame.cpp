#include "sim/i420_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gimbal::sim {

namespace {

constexpr int max_side = 16384;

std::size_t index(int px, int py, int stride) {
    return static_cast<std::size_t>(py) * static_cast<std::size_t>(stride) +
           static_cast<std::size_t>(px);
}

std::uint8_t clamp_byte(double v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

}  // namespace

bool I420Frame::resize(int new_width, int new_height) {
    if (new_width < 2 || new_height < 2 || new_width > max_side || new_height > max_side ||
        new_width % 2 != 0 || new_height % 2 != 0)
        return false;
    width = new_width;
    height = new_height;
    y.resize(index(0, height, width));
    u.resize(index(0, chroma_height(), chroma_width()));
    v.resize(u.size());
    return true;
}

std::uint8_t I420Frame::luma(int px, int py) const {
    return y[index(px, py, width)];
}

std::uint8_t I420Frame::cb(int px, int py) const {
    return u[index(px / 2, py / 2, chroma_width())];
}

std::uint8_t I420Frame::cr(int px, int py) const {
    return v[index(px / 2, py / 2, chroma_width())];
}

Yuv to_yuv(Rgb c) {
    const double r = c.r, g = c.g, b = c.b;
    return {clamp_byte(16 + (65.481 * r + 128.553 * g + 24.966 * b) / 255),
            clamp_byte(128 + (-37.797 * r - 74.203 * g + 112.0 * b) / 255),
            clamp_byte(128 + (112.0 * r - 93.786 * g - 18.214 * b) / 255)};
}

}  // namespace gimbal::sim
