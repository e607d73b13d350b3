// OpenCV's single-object trackers from the tracking module (opencv_contrib), behind one small
// interface: CSRT (discriminative correlation filter with channel and spatial reliability:
// robust, costly) and KCF (kernelized correlation filter: cheap). OpenCV's exceptions stay
// in here: a failure is a value. OpenCV 4.6's own success flag is only one input to the
// confidence (confidence.hpp): it is not a confidence.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>

#include "track/box.hpp"
#include "track/wire/messages.hpp"

namespace gimbal::track {

class CvTracker {
  public:
    static std::unique_ptr<CvTracker> create(wire::TrackerKind kind);
    virtual ~CvTracker() = default;

    // Learns the object in `box` of `frame` (BGR or grey). False when OpenCV refuses.
    virtual bool init(const cv::Mat& frame, const Box& box) = 0;
    // The object's box in the next frame; nullopt when the tracker reports failure.
    virtual std::optional<Box> update(const cv::Mat& frame) = 0;
    virtual wire::TrackerKind kind() const = 0;
};

}  // namespace gimbal::track
