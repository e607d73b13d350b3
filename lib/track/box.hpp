// A box in a picture, in pixels: continuous coordinates, 0 the left (top) edge of the first
// column (row), width (height) the right (bottom) edge of the last - the convention of
// cv::Rect2d. Conversions to and from contract section 16's image coordinates (-1..1 across
// the picture, x right, y down). Pure.
#pragma once

#include <algorithm>
#include <cmath>

namespace gimbal::track {

struct Point {
    double x = 0;
    double y = 0;
};

struct Box {
    double x0 = 0;
    double y0 = 0;
    double x1 = 0;
    double y1 = 0;

    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    double area() const { return std::max(0.0, width()) * std::max(0.0, height()); }
    Point centre() const { return {(x0 + x1) / 2, (y0 + y1) / 2}; }
    bool valid() const {
        return std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1) &&
               x1 > x0 && y1 > y0;
    }

    static Box around(Point c, double w, double h) {
        return {c.x - w / 2, c.y - h / 2, c.x + w / 2, c.y + h / 2};
    }
    Box moved_to(Point c) const { return around(c, width(), height()); }
    Box scaled(double kx, double ky) const { return {x0 * kx, y0 * ky, x1 * kx, y1 * ky}; }
};

// The part of `box` inside a picture of width x height, as a fraction of its area.
inline double inside_fraction(const Box& box, double width, double height) {
    const Box in{std::max(0.0, box.x0), std::max(0.0, box.y0), std::min(width, box.x1),
                 std::min(height, box.y1)};
    if (in.x1 <= in.x0 || in.y1 <= in.y0 || box.area() <= 0) return 0;
    return in.area() / box.area();
}

// Section 16 image coordinates <-> pixels of a width x height picture.
inline Box from_image(const Box& image, double width, double height) {
    return {(image.x0 + 1) / 2 * width, (image.y0 + 1) / 2 * height, (image.x1 + 1) / 2 * width,
            (image.y1 + 1) / 2 * height};
}
inline Box to_image(const Box& pixels, double width, double height) {
    return {pixels.x0 / width * 2 - 1, pixels.y0 / height * 2 - 1, pixels.x1 / width * 2 - 1,
            pixels.y1 / height * 2 - 1};
}

}  // namespace gimbal::track
