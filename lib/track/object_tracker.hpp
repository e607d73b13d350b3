// One object followed through decoded frames (docs/tracking.md "The engine"): an OpenCV
// tracker (CSRT or KCF) proposes a box each frame; a confidence computed here decides whether
// it is still the object; below the threshold - or when the object leaves the picture - the
// track is lost, and a re-detection search around the position predicted by the object's
// image motion looks for it again, frame after frame, in a window that grows with the time
// lost. A match good enough re-initialises the tracker on it and the track goes on. Whether
// a lost track has lasted too long is the caller's (TrackStateMachine). Frames are BGR or
// grey, 8-bit, all of one size; time in seconds is passed in.
#pragma once

#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "track/appearance.hpp"
#include "track/box.hpp"
#include "track/cv_tracker.hpp"
#include "track/image_motion.hpp"
#include "track/wire/messages.hpp"

namespace gimbal::track {

struct ObjectTrackerOptions {
    wire::TrackerKind tracker = wire::TrackerKind::kcf;
    double lost_threshold = 0.4;        // a frame below this confidence is a miss
    int misses_to_lose = 1;             // consecutive misses that make the track lost
    double update_threshold = 0.6;      // the template learns only from frames at least this sure
    double template_rate = 0.08;        // how fast it learns
    int template_long_side = 32;        // template size (pixels along the longer side)
    double accept_threshold = 0.75;     // a re-detection match must correlate at least this well,
                                        // in two frames running at consistent places
    double reacquire_confidence = 0.6;  // and the found box's confidence at least this
    double search_margin = 1.0;         // the window reaches this many box sizes beyond the box
    double search_growth_per_s = 1.0;   // ... plus this many per second lost
    double max_search_margin = 4.0;     // ... up to this many
    std::array<double, 3> scales{0.9, 1.0, 1.1};
    double min_box_px = 6;          // a box narrower or lower than this is refused at start
    double max_box_fraction = 0.5;  // a box wider or higher than this part of the frame too
    // Confidence terms (docs/tracking.md): appearance, distinctness, motion.
    double ncc_floor = 0.3;        // template correlation at which appearance counts nothing
    double ncc_full = 0.8;         // ... and fully
    double colour_floor = 0.75;    // colour similarity with the object at which appearance
    double colour_full = 0.92;     // counts nothing, and fully (the better of the two counts)
    double distinct_floor = 0.12;  // distinctness at which the box counts as ground
    double distinct_full = 0.3;
    double distinct_ratio_floor = 0.35;  // ... and relative to the object's own at the start:
    double distinct_ratio_full = 0.65;   // a box that stands out much less is not it
    double structure_floor = 1.5;        // fine detail (grey levels) at which the box counts as
    double structure_full = 3.5;         // featureless (sky, haze, a smooth wall), and fully
    double motion_sigma = 0.75;          // a jump from the prediction, in box sizes, that halves
                                         // the motion term about ... (exp(-d^2 / 2 sigma^2))
    double left_picture_fraction = 0.5;  // less of the box inside the picture: lost
};

// The parts of a frame's confidence (for logs and tests).
struct ConfidenceParts {
    bool tracker_ok = false;
    double ncc = 0;
    double colour = 0;  // similarity of the box's colours with the object's
    double distinctness = 0;
    double distinct_ratio = 0;  // distinctness / the start's
    double structure = 0;       // fine detail in the box (grey levels)
    double motion = 0;
    double size = 0;
};

struct FrameResult {
    Box box;                // pixels; when lost, the predicted box
    double confidence = 0;  // 0..1; when lost, below the lost threshold
    bool lost = false;
    bool became_lost = false;
    bool reacquired = false;
    bool left_picture = false;  // lost because the box left the picture
    ConfidenceParts parts;
    double search_score = 0;  // the best re-detection match this frame (when lost)
};

class ObjectTracker {
  public:
    struct Started {
        std::unique_ptr<ObjectTracker> tracker;
        std::string error;  // when tracker is null
        FrameResult first;  // the first frame's result (its confidence says whether the box
                            // holds anything worth following)
    };
    static Started start(const cv::Mat& frame, const Box& box, double t,
                         const ObjectTrackerOptions& options = {});

    FrameResult update(const cv::Mat& frame, double t);

    bool lost() const { return lost_; }
    cv::Size frame_size() const { return size_; }
    const ObjectTrackerOptions& options() const { return o_; }
    Point velocity() const { return motion_.velocity(); }

  private:
    ObjectTracker(const ObjectTrackerOptions& options, std::unique_ptr<CvTracker> tracker);

    FrameResult track(const cv::Mat& frame, double t);
    FrameResult search(const cv::Mat& frame, double t);
    FrameResult lose(const Box& box, double confidence, const ConfidenceParts& parts,
                     bool left_picture, double t);
    double confidence(const ConfidenceParts& parts) const;
    ConfidenceParts measure(const cv::Mat& frame, const Box& box, bool tracker_ok, double t,
                            const cv::Mat* templ = nullptr) const;
    void learn(const cv::Mat& frame, const Box& box);
    void rescale(cv::Size to);

    ObjectTrackerOptions o_;
    std::unique_ptr<CvTracker> tracker_;
    ImageMotion motion_;
    cv::Size size_;
    cv::Mat template_;
    Histogram colours_{};
    double box_w_ = 0, box_h_ = 0;  // the object's size, pixels
    double start_area_ = 0;
    double start_distinct_ = 0;
    bool confident_template_ = false;  // learnt from a confident frame: worth searching for
    struct Pending {
        Point centre;
        double t = 0;
        int quarter_turns = 0;
    };
    std::optional<Pending> pending_;  // a match waiting for its confirmation
    Box last_box_;
    bool lost_ = false;
    int misses_ = 0;
    double lost_since_ = 0;
};

}  // namespace gimbal::track
