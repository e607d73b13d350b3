// The re-detection search (docs/tracking.md "Re-acquisition"): where in a window around the
// predicted position the object's last confident template matches best, at a few scales.
// OpenCV's trackers do not find an object again once it was hidden; this does.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <span>

#include "track/box.hpp"

namespace gimbal::track {

struct SearchRequest {
    const cv::Mat* templ = nullptr;  // the template (grey CV_32F, patch_size of `size`)
    double width = 0;                // the object's box size (pixels) the template shows
    double height = 0;
    Point predicted;                 // where its centre is expected
    double margin = 0;               // how far beyond the box to look (pixels, each side)
    std::span<const double> scales;  // box sizes tried, relative to width x height
    bool turns = true;               // also the template turned by 90, 180 and 270 degrees:
                                     // a vehicle that turned a corner while hidden or lost
};

struct Candidate {
    Box box;
    double score = 0;       // normalised cross-correlation with the template, -1..1
    int quarter_turns = 0;  // how the template was turned (clockwise, 0..3)
};

// The template turned clockwise by quarter_turns x 90 degrees.
cv::Mat turned(const cv::Mat& templ, int quarter_turns);

// The best match in the window (clipped to the frame); nullopt when the window is smaller
// than the object.
std::optional<Candidate> search(const cv::Mat& frame, const SearchRequest& request);

}  // namespace gimbal::track
