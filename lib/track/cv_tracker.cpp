#include "track/cv_tracker.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>

namespace gimbal::track {

namespace {

// KCF's own settings (OpenCV's defaults: 0.5 and 0.075). Its detection threshold gives up
// on a vehicle turning at a street corner while the box is still on it; the confidence
// computed here decides instead. A faster model update follows the turning shape.
constexpr float kcf_detect_thresh = 0.2f;
constexpr float kcf_interp_factor = 0.15f;

cv::Rect to_rect(const Box& b) {
    const int x0 = static_cast<int>(std::lround(b.x0));
    const int y0 = static_cast<int>(std::lround(b.y0));
    return {x0, y0, std::max(1, static_cast<int>(std::lround(b.x1)) - x0),
            std::max(1, static_cast<int>(std::lround(b.y1)) - y0)};
}

class OpenCvTracker final : public CvTracker {
  public:
    explicit OpenCvTracker(wire::TrackerKind kind) : kind_(kind) {}

    bool init(const cv::Mat& input, const Box& box) override {
        try {
            const cv::Mat& frame = colour(input);
            tracker_ = make();
            const cv::Rect r = to_rect(box) & cv::Rect(0, 0, frame.cols, frame.rows);
            if (r.width < 2 || r.height < 2) return false;
            tracker_->init(frame, r);
            if (kind_ == wire::TrackerKind::kcf) {
                // OpenCV 4.6's KCF does not detect in its first update() after init(): it
                // learns the new frame at the old position, and from then on reports every
                // box one frame's motion behind the object. Spending that update on the
                // initial frame itself keeps the model centred (tests/unit/track).
                cv::Rect ignored;
                tracker_->update(frame, ignored);
            }
            return true;
        } catch (const cv::Exception&) {
            tracker_.release();
            return false;
        }
    }

    std::optional<Box> update(const cv::Mat& input) override {
        if (!tracker_) return std::nullopt;
        try {
            cv::Rect r;
            if (!tracker_->update(colour(input), r) || r.width <= 0 || r.height <= 0)
                return std::nullopt;
            return Box{static_cast<double>(r.x), static_cast<double>(r.y),
                       static_cast<double>(r.x + r.width), static_cast<double>(r.y + r.height)};
        } catch (const cv::Exception&) {
            return std::nullopt;
        }
    }

    wire::TrackerKind kind() const override { return kind_; }

  private:
    // OpenCV's KCF and CSRT describe colour (colour names): a grey frame goes in as BGR, as
    // a monochrome (infrared) camera's decoded video does anyway.
    const cv::Mat& colour(const cv::Mat& frame) {
        if (frame.channels() != 1) return frame;
        cv::cvtColor(frame, bgr_, cv::COLOR_GRAY2BGR);
        return bgr_;
    }

    cv::Ptr<cv::Tracker> make() const {
        if (kind_ == wire::TrackerKind::csrt) return cv::TrackerCSRT::create();
        cv::TrackerKCF::Params kcf;
        kcf.detect_thresh = kcf_detect_thresh;
        kcf.interp_factor = kcf_interp_factor;
        return cv::TrackerKCF::create(kcf);
    }

    wire::TrackerKind kind_;
    cv::Ptr<cv::Tracker> tracker_;
    cv::Mat bgr_;
};

}  // namespace

std::unique_ptr<CvTracker> CvTracker::create(wire::TrackerKind kind) {
    return std::make_unique<OpenCvTracker>(kind);
}

}  // namespace gimbal::track
