// The `track` command's parameters (contract section 20): a point `x`,`y` with a box of
// `size` (a fraction of the image width) around it, or a box `x0`,`y0`,`x1`,`y1`; each also
// in pixels (`px`,`py`; `px0`..`py1`). Read and checked here into one box in section 16 image
// coordinates, the form gimbal-track is given. Pure.
#pragma once

#include <optional>

#include "command/params.hpp"
#include "command/result.hpp"
#include "session/capabilities.hpp"

namespace gimbal::session {

inline constexpr double default_track_size = 0.08;

struct TrackBox {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // -1..1, x1 > x0, y1 > y0
};

struct TrackRequest {
    TrackBox box;
    std::optional<bool> steer;  // none: the configuration's
};

// The image's width over its height: from its pixel size when known, else from the fields of
// view (square pixels); nullopt when neither is known.
std::optional<double> image_aspect(const ImageView& view);

// Reads and checks the parameters (the catalogue's ranges, one form only, a box that is not
// empty and lies in the picture). A point's box is clipped to the picture. `view` converts
// pixels and gives the aspect for a point's box.
command::Result<TrackRequest> read_track_request(command::JsonParams& p, const ImageView& view);

}  // namespace gimbal::session
