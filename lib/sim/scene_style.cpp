#include "sim/scene_style.hpp"

#include <array>

namespace gimbal::sim::scene {

Rgb landmark_colour(std::size_t index) {
    // Red, yellow, magenta, cyan, blue: hues 60 degrees or more apart, none of them green.
    static constexpr std::array<Rgb, 5> palette{{
        {220, 30, 30},
        {235, 220, 30},
        {220, 40, 220},
        {30, 210, 230},
        {40, 50, 230},
    }};
    return palette[index % palette.size()];
}

}  // namespace gimbal::sim::scene
