#include <catch2/catch.hpp>

#include "protocols/orion/sim/camera.hpp"
#include "sim/frames.hpp"

using namespace gimbal::sim;

TEST_CASE("zoom narrows the field of view down to the longest focal length", "[sim][camera]") {
    gimbal::orion::CameraSettings c;
    c.min_focal_length_mm = 10;
    c.max_focal_length_mm = 40;
    c.pixel_pitch_mm = 0.01;
    c.array_width = 2000;  // 20 mm wide
    c.array_height = 1000;
    const FieldOfView wide = field_of_view(c, 1);
    CHECK(wide.horizontal == Approx(2 * std::atan(1.0)));
    CHECK(wide.vertical == Approx(2 * std::atan(0.5)));
    CHECK(field_of_view(c, 2).horizontal == Approx(2 * std::atan(0.5)));
    CHECK(field_of_view(c, 10).horizontal == Approx(2 * std::atan(0.25)));
    CHECK(field_of_view(c, 0.2).horizontal == Approx(wide.horizontal));
    c.pixel_pitch_mm = 0;
    CHECK(field_of_view(c, 1).horizontal == 0);
}
