#include "session/track_request.hpp"

#include "session/image_commands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace gimbal::session {

namespace code = command::code;
using command::Error;

namespace {

constexpr std::array<const char*, 4> box_keys{"x0", "y0", "x1", "y1"};
constexpr std::array<const char*, 4> pixel_box_keys{"px0", "py0", "px1", "py1"};

bool any_of(command::JsonParams& p, const std::array<const char*, 4>& keys) {
    return std::any_of(keys.begin(), keys.end(), [&p](const char* k) { return p.has(k); });
}

// The four values of one box form, every one required once any is given.
command::Result<std::array<double, 4>> read_box(command::JsonParams& p,
                                                const std::array<const char*, 4>& keys) {
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto value = p.number(keys[i], false);
        if (!p.ok()) return p.error();
        if (!value)
            return Error{code::bad_request, std::string("missing parameter '") + keys[i] +
                                                "' (a box needs all four edges)"};
        v[i] = *value;
    }
    return v;
}

command::Result<std::array<double, 2>> image_size(const ImageView& view) {
    if (!view.width_px || !view.height_px || *view.width_px <= 0 || *view.height_px <= 0)
        return Error{code::unavailable,
                     "the gimbal reports no image size (pixel_width, pixel_height): use 'x','y'"};
    return std::array<double, 2>{*view.width_px, *view.height_px};
}

command::Result<TrackBox> checked(TrackBox b) {
    if (!(b.x1 > b.x0) || !(b.y1 > b.y0))
        return Error{code::bad_request, "the box is empty: x1 must exceed x0 and y1 exceed y0"};
    return b;
}

command::Result<TrackBox> point_box(command::JsonParams& p, const ImageView& view) {
    const auto position = read_image_position(p);
    const double size = p.number_or("size", default_track_size);
    if (!p.ok()) return p.error();
    if (!position) return position.error();
    const auto at = image_point(*position, view);
    if (!at) return at.error();
    const auto aspect = image_aspect(view);
    if (!aspect)
        return Error{code::unavailable, "the gimbal reports no image size or field of view"};
    // -1..1 spans the width: a side of `size` widths is 2 x size across, and as many pixels
    // down, which is 2 x size x aspect of the height.
    const double half_x = size, half_y = size * *aspect;
    TrackBox b{std::max(-1.0, at->x - half_x), std::max(-1.0, at->y - half_y),
               std::min(1.0, at->x + half_x), std::min(1.0, at->y + half_y)};
    return checked(b);
}

}  // namespace

std::optional<double> image_aspect(const ImageView& view) {
    if (view.width_px && view.height_px && *view.width_px > 0 && *view.height_px > 0)
        return *view.width_px / *view.height_px;
    const double h = view.camera.hfov_deg * std::numbers::pi / 360;
    const double v = view.camera.vfov_deg * std::numbers::pi / 360;
    if (h > 0 && v > 0 && h < std::numbers::pi / 2 && v < std::numbers::pi / 2)
        return std::tan(h) / std::tan(v);
    return std::nullopt;
}

command::Result<TrackRequest> read_track_request(command::JsonParams& p, const ImageView& view) {
    const bool point = p.has("x") || p.has("y") || p.has("px") || p.has("py");
    const bool box = any_of(p, box_keys);
    const bool pixel_box = any_of(p, pixel_box_keys);
    TrackRequest out;
    out.steer = p.boolean("steer", false);
    if (!p.ok()) return p.error();
    if (int(point) + int(box) + int(pixel_box) > 1)
        return Error{code::bad_request,
                     "give one of a point ('x','y' or 'px','py'), a box ('x0','y0','x1','y1') "
                     "or a box in pixels ('px0','py0','px1','py1')"};
    if (!point && !box && !pixel_box)
        return Error{code::bad_request,
                     "missing parameters: a point 'x','y' or a box 'x0','y0','x1','y1'"};
    if ((box || pixel_box) && p.has("size"))
        return Error{code::bad_request, "'size' is for a point, not a box"};
    command::Result<TrackBox> b = TrackBox{};
    if (point) {
        b = point_box(p, view);
    } else if (box) {
        const auto v = read_box(p, box_keys);
        if (!v) return v.error();
        b = checked({(*v)[0], (*v)[1], (*v)[2], (*v)[3]});
    } else {
        const auto v = read_box(p, pixel_box_keys);
        if (!v) return v.error();
        const auto size = image_size(view);
        if (!size) return size.error();
        const auto [w, h] = *size;
        if ((*v)[2] > w || (*v)[3] > h)
            return Error{code::out_of_range, "the box reaches beyond the image (" +
                                                 command::format_number(w) + " x " +
                                                 command::format_number(h) + " pixels)"};
        b = checked(
            {(*v)[0] / w * 2 - 1, (*v)[1] / h * 2 - 1, (*v)[2] / w * 2 - 1, (*v)[3] / h * 2 - 1});
    }
    if (!b) return b.error();
    out.box = *b;
    return out;
}

}  // namespace gimbal::session
