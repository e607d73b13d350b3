// Colours as the scene renderer mixes them: offsets from black (Y - 16, U - 128, V - 128), in
// which blends and shading of RGB are linear too. Internal to lib/sim's renderer.
#pragma once

#include <algorithm>

#include "sim/i420_frame.hpp"

namespace gimbal::sim {

struct Colour {
    float y = 0;
    float u = 0;
    float v = 0;
};

inline Colour offset(Rgb c) {
    const Yuv q = to_yuv(c);
    return {static_cast<float>(q.y) - 16.f, static_cast<float>(q.u) - 128.f,
            static_cast<float>(q.v) - 128.f};
}

inline Colour lerp(Colour a, Colour b, float t) {
    return {a.y + (b.y - a.y) * t, a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t};
}

inline Colour scaled(Colour a, float k) {
    return {a.y * k, a.u * k, a.v * k};
}

// min/max rather than std::clamp: branch-free in the pixel loop.
inline float clamp01(float v) {
    return std::min(std::max(v, 0.f), 1.f);
}

}  // namespace gimbal::sim
