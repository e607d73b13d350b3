// What the confidence and the re-detection search look at (docs/tracking.md "Confidence"):
// a box's grey patch at a fixed small size, the normalised cross-correlation of two patches,
// and how much a box stands out from the ground around it.
#pragma once

#include <array>
#include <opencv2/core.hpp>

#include "track/box.hpp"

namespace gimbal::track {

// The size a box's patch is compared at: `long_side` pixels along its longer side, the
// aspect kept, at least 4 pixels each way.
cv::Size patch_size(const Box& box, int long_side);

// The grey (CV_32F) picture of `box` in `frame` (BGR or grey, 8-bit) resized to `size`; the
// part of the box outside the frame repeats the frame's edge.
cv::Mat grey_patch(const cv::Mat& frame, const Box& box, cv::Size size);

// Normalised cross-correlation of two patches of the same size, -1..1; 0 when either is
// flat (a standard deviation under flat_sigma grey levels: sky, a blank wall, a smooth
// road), since nothing can be recognised there.
inline constexpr double flat_sigma = 3.0;
double ncc(const cv::Mat& a, const cv::Mat& b);

// How much fine detail a grey patch (grey_patch) holds: the standard deviation, in grey
// levels, of what is left after a blur - edges, corners, markings. A smooth gradient (sky,
// haze) has almost none, a vehicle a lot.
double structure(const cv::Mat& grey_patch);

// A box's colours, twice: a colour histogram (4 levels per channel, 64 bins; 16 grey levels
// for grey frames) and a luma histogram (16 levels, 16 bins), each normalised to sum 1 (all
// zero for an empty box). The luma part tells grey things apart - a monochrome camera's BGR
// has only 4 colour bins in use. Blind to rotation, unlike a patch.
using Histogram = std::array<double, 80>;
Histogram colour_histogram(const cv::Mat& frame, const Box& box);
// The Bhattacharyya coefficient of two histograms, the smaller of their colour and luma
// parts': 1 the same, 0 nothing in common.
double similarity(const Histogram& a, const Histogram& b);

// How different the box's colours are from those of the ring of ground around it (half the
// box's size on each side): the Bhattacharyya distance sqrt(1 - similarity) between their
// histograms, 0 (the same) .. 1 (nothing in common). An object on the ground stands out; a
// box on empty ground or sky does not.
double distinctness(const cv::Mat& frame, const Box& box);

}  // namespace gimbal::track
