// The image commands gimbald answers itself (contract section 16) - `locate`, `project` and
// `point` - from a gimbal's image geometry (Capabilities::image) and the ground
// (geo/ground.hpp): parameters read and checked, replies built, the pointing request made
// through the gimbal's geopoint capability. No protocol is named here. Pure apart from what
// the terrain surface reads.
#pragma once

#include <nlohmann/json.hpp>

#include "command/params.hpp"
#include "command/result.hpp"
#include "geo/ground.hpp"
#include "session/capabilities.hpp"

namespace gimbal::session {

// An image position as a request gives it: normalised `x`,`y` or pixel `px`,`py`.
struct ImagePosition {
    bool pixels = false;
    double a = 0;  // x or px
    double b = 0;  // y or py
};

// Reads x,y (each -1..1) or px,py (each 0..65535; the image's size is checked later). One
// pair, whole: both or neither of a pair, never both pairs. Errors name the keys.
command::Result<ImagePosition> read_image_position(command::JsonParams& p);

// The normalised point: pixels converted with the image's size (out_of_range beyond it,
// unavailable when the gimbal reports no size).
command::Result<geo::ImagePoint> image_point(const ImagePosition& position, const ImageView& view);

// The ground seen there (terrain where it answers, else the ellipsoid at the flat world's
// altitude); unavailable when the ray meets neither, naming why.
command::Result<geo::GroundPoint> locate_point(const ImageView& view, geo::ImagePoint p,
                                               geo::Surface* terrain);

// `project`'s reply for a point: "x", "y" (null behind the camera), "visible" (in the image
// and, with a terrain, not hidden by it), "px"/"py" when the image size is known.
nlohmann::json project_reply(const ImageView& view, const geo::Lla& point, geo::Surface* terrain);

// The request (for the request path) that points the gimbal at `target` through its geopoint
// capability, staring when `stare` and the gimbal's geopoint takes `stare`. unsupported when
// the gimbal cannot point at a location (or stare); unavailable when it reports no geoid
// undulation to give the altitude above mean sea level with.
Request point_request(const Capabilities& capabilities, const ImageView& view,
                      const geo::GroundPoint& target, bool stare);

}  // namespace gimbal::session
