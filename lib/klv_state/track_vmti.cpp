#include "klv_state/track_vmti.hpp"

#include <algorithm>
#include <cmath>

namespace gimbal::klv_state {

std::uint32_t pixel_index(double image_coordinate, int pixels) {
    // -1 is the outer edge of the first pixel and +1 that of the last; off-image (or NaN)
    // coordinates are held to the edge pixels.
    const double from_edge = (image_coordinate + 1.0) / 2.0 * pixels;
    const double index = std::isfinite(from_edge) ? std::floor(from_edge) : 0.0;
    return static_cast<std::uint32_t>(std::clamp(index, 0.0, pixels - 1.0)) + 1;
}

std::optional<klv::VmtiSet> track_vmti(const state::TrackState& track, std::optional<int> width,
                                       std::optional<int> height) {
    if (!width || !height || *width <= 0 || *height <= 0) return std::nullopt;
    const auto w = static_cast<std::uint32_t>(*width);
    const auto pixel = [&](double x, double y) {
        return klv::vmti_pixel_number(pixel_index(y, *height), pixel_index(x, *width), w);
    };
    klv::VmtiTarget t;
    t.id = track.id;
    t.centroid = pixel(track.centre.x, track.centre.y);
    const state::TrackImageBox& b = track.box;
    t.top_left = pixel(std::min(b.x0, b.x1), std::min(b.y0, b.y1));
    t.bottom_right = pixel(std::max(b.x0, b.x1), std::max(b.y0, b.y1));
    const double pct = std::isfinite(track.confidence) ? track.confidence * 100.0 : 0.0;
    t.confidence_pct = static_cast<std::uint8_t>(std::lround(std::clamp(pct, 0.0, 100.0)));
    if (track.ground && std::isfinite(track.ground->lat) && std::isfinite(track.ground->lon) &&
        std::isfinite(track.ground->alt))
        t.location = klv::VmtiLocation{track.ground->lat, track.ground->lon, track.ground->alt};
    klv::VmtiSet set;
    set.total_targets = 1;
    set.reported_targets = 1;
    set.frame_width = w;
    set.frame_height = static_cast<std::uint32_t>(*height);
    set.targets.push_back(std::move(t));
    return set;
}

}  // namespace gimbal::klv_state
