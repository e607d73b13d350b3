#include "session/image_commands.hpp"

#include <cmath>
#include <string>

#include "command/catalogue.hpp"
#include "state/ground_json.hpp"
#include "state/precision.hpp"

namespace gimbal::session {

namespace {

using command::Error;
using nlohmann::json;
namespace code = command::code;

}  // namespace

command::Result<ImagePosition> read_image_position(command::JsonParams& p) {
    const bool has_x = p.has("x"), has_y = p.has("y");
    const bool has_px = p.has("px"), has_py = p.has("py");
    const auto x = p.number("x", false);
    const auto y = p.number("y", false);
    const auto px = p.number("px", false);
    const auto py = p.number("py", false);
    if (!p.ok()) return p.error();
    const bool normalised = has_x || has_y;
    const bool pixels = has_px || has_py;
    if (normalised && pixels)
        return Error{code::bad_request, "give 'x','y' or 'px','py', not both"};
    if (!normalised && !pixels)
        return Error{code::bad_request, "missing parameters 'x','y' (or 'px','py')"};
    if (normalised) {
        if (!x) return Error{code::bad_request, "missing parameter 'x' (with 'y')"};
        if (!y) return Error{code::bad_request, "missing parameter 'y' (with 'x')"};
        return ImagePosition{false, *x, *y};
    }
    if (!px) return Error{code::bad_request, "missing parameter 'px' (with 'py')"};
    if (!py) return Error{code::bad_request, "missing parameter 'py' (with 'px')"};
    return ImagePosition{true, *px, *py};
}

command::Result<geo::ImagePoint> image_point(const ImagePosition& position, const ImageView& view) {
    if (!position.pixels) return geo::ImagePoint{position.a, position.b};
    if (!view.width_px || !view.height_px)
        return Error{code::unavailable,
                     "the gimbal reports no image size (pixel_width, pixel_height): use 'x','y'"};
    const double w = *view.width_px, h = *view.height_px;
    if (position.a > w)
        return Error{code::out_of_range,
                     "'px' must be between 0 and " + command::format_number(w) + " (pixel_width)"};
    if (position.b > h)
        return Error{code::out_of_range,
                     "'py' must be between 0 and " + command::format_number(h) + " (pixel_height)"};
    const auto p = geo::from_pixels({position.a, position.b}, w, h);
    if (!p) return Error{code::unavailable, "the gimbal's image size is not usable"};
    return *p;
}

command::Result<geo::GroundPoint> locate_point(const ImageView& view, geo::ImagePoint p,
                                               geo::Surface* terrain) {
    geo::RayStatus why = geo::RayStatus::unknown;
    const auto g = geo::locate_ground(view.camera, p, {terrain, view.flat_alt_m}, &why);
    if (g) return *g;
    std::string reason;
    switch (why) {
        case geo::RayStatus::no_ground:
            reason = "the ray does not reach the ground (above the horizon or out of range)";
            break;
        case geo::RayStatus::below_surface:
            reason = "the camera is below the ground";
            break;
        case geo::RayStatus::invalid:
            reason = "the gimbal's telemetry gives no usable camera";
            break;
        case geo::RayStatus::unknown:
        case geo::RayStatus::hit:
            reason = terrain ? "the ray leaves the terrain's coverage and the gimbal reports no "
                               "target altitude for the flat world"
                             : "no terrain is configured and the gimbal reports no target "
                               "altitude for the flat world";
            break;
    }
    return Error{code::unavailable, "no ground point there: " + reason};
}

json project_reply(const ImageView& view, const geo::Lla& point, geo::Surface* terrain) {
    json out = {{"x", nullptr}, {"y", nullptr}, {"visible", false}};
    const auto p = geo::project(view.camera, point, terrain);
    if (!p || !p->in_front) return out;
    // Image coordinates as numbers of the contract's precision (1e-6 of the half-width is
    // well under a pixel of any camera).
    out["x"] = state::round_decimals(p->at.x, 6);
    out["y"] = state::round_decimals(p->at.y, 6);
    out["visible"] = p->visible;
    if (view.width_px && view.height_px)
        if (const auto px = geo::to_pixels(p->at, *view.width_px, *view.height_px)) {
            out["px"] = state::round_decimals(px->px, 3);
            out["py"] = state::round_decimals(px->py, 3);
        }
    return out;
}

Request point_request(const Capabilities& capabilities, const ImageView& view,
                      const geo::GroundPoint& target, bool stare) {
    if (!capabilities.features().geopoint)
        return unsupported("this gimbal cannot point at a location (no geopoint capability)");
    if (!view.geoid_undulation_m)
        return unavailable("the gimbal reports no geoid undulation for the point's altitude");
    Request request = capabilities.geopoint(
        GeoTarget{target.point.lat_deg, target.point.lon_deg,
                  geo::msl_from_ellipsoid(target.point.alt_m, *view.geoid_undulation_m)});
    if (!request || !stare) return request;
    // Stare where the command the capability chose takes it (the catalogue says).
    const auto* cmd = request->contains("cmd") && (*request)["cmd"].is_string()
                          ? command::find_command((*request)["cmd"].get<std::string>())
                          : nullptr;
    if (!cmd || !command::find_param(*cmd, "stare"))
        return unsupported("this gimbal cannot stare at a location");
    (*request)["stare"] = true;
    return request;
}

}  // namespace gimbal::session
