#include "track/object_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "track/appearance.hpp"
#include "track/redetect.hpp"

namespace gimbal::track {

namespace {

double ramp(double value, double floor, double full) {
    if (full <= floor) return value >= full ? 1 : 0;
    return std::clamp((value - floor) / (full - floor), 0.0, 1.0);
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}

bool usable(const cv::Mat& frame) {
    return !frame.empty() && frame.depth() == CV_8U &&
           (frame.channels() == 1 || frame.channels() == 3);
}

}  // namespace

ObjectTracker::ObjectTracker(const ObjectTrackerOptions& options,
                             std::unique_ptr<CvTracker> tracker)
    : o_(options), tracker_(std::move(tracker)) {}

ObjectTracker::Started ObjectTracker::start(const cv::Mat& frame, const Box& box, double t,
                                            const ObjectTrackerOptions& options) {
    if (!usable(frame)) return {nullptr, "the frame is not an 8-bit BGR or grey picture", {}};
    if (!box.valid()) return {nullptr, "the box is empty", {}};
    const double w = frame.cols, h = frame.rows;
    const Box clipped{std::max(0.0, box.x0), std::max(0.0, box.y0), std::min(w, box.x1),
                      std::min(h, box.y1)};
    if (!clipped.valid() || clipped.width() < options.min_box_px ||
        clipped.height() < options.min_box_px)
        return {
            nullptr,
            "the box is smaller than " + number(options.min_box_px) + " pixels inside the picture",
            {}};
    if (clipped.width() > options.max_box_fraction * w ||
        clipped.height() > options.max_box_fraction * h)
        return {nullptr, "the box is larger than half the picture", {}};
    auto cv_tracker = CvTracker::create(options.tracker);
    if (!cv_tracker->init(frame, clipped)) return {nullptr, "the tracker refused the box", {}};

    std::unique_ptr<ObjectTracker> self(new ObjectTracker(options, std::move(cv_tracker)));
    self->size_ = frame.size();
    self->template_ = grey_patch(frame, clipped, patch_size(clipped, options.template_long_side));
    self->box_w_ = clipped.width();
    self->box_h_ = clipped.height();
    self->start_area_ = clipped.area();
    self->start_distinct_ = distinctness(frame, clipped);
    self->colours_ = colour_histogram(frame, clipped);
    self->last_box_ = clipped;
    self->motion_.reset(clipped.centre(), t);

    FrameResult first;
    first.box = clipped;
    first.parts = self->measure(frame, clipped, true, t);
    first.confidence = self->confidence(first.parts);
    // Only what the operator boxed and the confidence accepts is searched for once lost: a
    // box on empty ground or sky is lost at once and stays lost.
    self->confident_template_ = first.confidence >= options.lost_threshold;
    if (!self->confident_template_)
        first = self->lose(clipped, first.confidence, first.parts, false, t);
    return {std::move(self), {}, first};
}

ConfidenceParts ObjectTracker::measure(const cv::Mat& frame, const Box& box, bool tracker_ok,
                                       double t, const cv::Mat* templ) const {
    if (templ == nullptr) templ = &template_;
    ConfidenceParts p;
    p.tracker_ok = tracker_ok;
    const cv::Mat patch = grey_patch(frame, box, templ->size());
    p.ncc = ncc(patch, *templ);
    p.structure = structure(patch);
    p.colour = similarity(colour_histogram(frame, box), colours_);
    p.distinctness = distinctness(frame, box);
    p.distinct_ratio = start_distinct_ > 0 ? p.distinctness / start_distinct_ : 0;
    const Point predicted = motion_.predict(t);
    const Point c = box.centre();
    const double jump =
        std::hypot(c.x - predicted.x, c.y - predicted.y) / std::max(1.0, std::max(box_w_, box_h_));
    p.motion = std::exp(-0.5 * jump * jump / (o_.motion_sigma * o_.motion_sigma));
    const double ratio = box.area() / std::max(1.0, start_area_);
    p.size = std::clamp(std::min(ratio / 0.5, 2.0 / ratio), 0.0, 1.0);
    return p;
}

double ObjectTracker::confidence(const ConfidenceParts& p) const {
    if (!p.tracker_ok) return 0;
    const double appearance = std::max(ramp(p.ncc, o_.ncc_floor, o_.ncc_full),
                                       ramp(p.colour, o_.colour_floor, o_.colour_full));
    return appearance * ramp(p.distinctness, o_.distinct_floor, o_.distinct_full) *
           ramp(p.distinct_ratio, o_.distinct_ratio_floor, o_.distinct_ratio_full) *
           ramp(p.structure, o_.structure_floor, o_.structure_full) * p.motion * p.size;
}

void ObjectTracker::learn(const cv::Mat& frame, const Box& box) {
    const cv::Mat patch = grey_patch(frame, box, template_.size());
    cv::addWeighted(template_, 1 - o_.template_rate, patch, o_.template_rate, 0, template_);
    const Histogram now = colour_histogram(frame, box);
    for (std::size_t i = 0; i < colours_.size(); ++i)
        colours_[i] += o_.template_rate * (now[i] - colours_[i]);
}

FrameResult ObjectTracker::lose(const Box& box, double confidence, const ConfidenceParts& parts,
                                bool left_picture, double t) {
    lost_ = true;
    lost_since_ = t;
    misses_ = 0;
    pending_.reset();
    FrameResult r;
    r.box = box;
    r.confidence = std::min(confidence, o_.lost_threshold * 0.99);
    r.lost = true;
    r.became_lost = true;
    r.left_picture = left_picture;
    r.parts = parts;
    return r;
}

FrameResult ObjectTracker::update(const cv::Mat& frame, double t) {
    if (!usable(frame)) {
        FrameResult r;
        r.box = Box::around(motion_.predict(t), box_w_, box_h_);
        r.lost = lost_;
        return r;
    }
    if (frame.size() != size_) rescale(frame.size());
    return lost_ ? search(frame, t) : track(frame, t);
}

FrameResult ObjectTracker::track(const cv::Mat& frame, double t) {
    const Box predicted = Box::around(motion_.predict(t), box_w_, box_h_);
    const auto proposal = tracker_->update(frame);
    const Box box = proposal ? *proposal : predicted;
    const ConfidenceParts parts = measure(frame, box, proposal.has_value(), t);
    const double conf = confidence(parts);
    if (inside_fraction(box, frame.cols, frame.rows) < o_.left_picture_fraction)
        return lose(predicted, conf, parts, true, t);
    if (conf < o_.lost_threshold) {
        if (++misses_ >= o_.misses_to_lose) return lose(predicted, conf, parts, false, t);
        FrameResult r;  // a miss not yet a loss: the box as proposed, its low confidence
        r.box = box;
        r.confidence = conf;
        r.parts = parts;
        return r;
    }
    misses_ = 0;
    motion_.update(box.centre(), t);
    if (conf >= o_.update_threshold) {
        learn(frame, box);
        confident_template_ = true;
    }
    box_w_ = box.width();
    box_h_ = box.height();
    last_box_ = box;
    FrameResult r;
    r.box = box;
    r.confidence = conf;
    r.parts = parts;
    return r;
}

FrameResult ObjectTracker::search(const cv::Mat& frame, double t) {
    const Point predicted = motion_.predict(t);
    FrameResult r;
    r.box = Box::around(predicted, box_w_, box_h_);
    r.lost = true;
    if (!confident_template_) return r;
    const double size = std::max(box_w_, box_h_);
    const double lost_for = std::max(0.0, t - lost_since_);
    SearchRequest request;
    request.templ = &template_;
    request.width = box_w_;
    request.height = box_h_;
    request.predicted = predicted;
    request.margin =
        size * std::min(o_.max_search_margin, o_.search_margin + o_.search_growth_per_s * lost_for);
    request.scales = o_.scales;
    const auto found = track::search(frame, request);
    if (!found) {
        pending_.reset();
        return r;
    }
    r.search_score = found->score;
    const cv::Mat templ = turned(template_, found->quarter_turns);
    ConfidenceParts parts = measure(frame, found->box, true, t, &templ);
    parts.motion = 1;  // the window already bounds how far it may be from the prediction
    const double conf = confidence(parts);
    r.parts = parts;
    r.confidence = std::clamp(std::min(found->score, conf), 0.0, o_.lost_threshold * 0.99);
    const bool good =
        found->score >= o_.accept_threshold && conf >= o_.reacquire_confidence &&
        inside_fraction(found->box, frame.cols, frame.rows) >= o_.left_picture_fraction;
    if (!good) {
        pending_.reset();
        return r;
    }
    // A good match is taken when the previous frame had one, the same way round, at a
    // consistent place: within a quarter of the object's size plus as far as the object
    // moves in that time at its speed, whichever way it turned. A lone match on something
    // that merely resembles the object does not re-acquire.
    const Point c = found->box.centre();
    const bool confirmed = pending_ && pending_->quarter_turns == found->quarter_turns && [&] {
        const Point v = motion_.velocity();
        const double reach = 0.25 * size + std::hypot(v.x, v.y) * (t - pending_->t);
        return std::hypot(c.x - pending_->centre.x, c.y - pending_->centre.y) <= reach;
    }();
    pending_ = Pending{c, t, found->quarter_turns};
    if (!confirmed || !tracker_->init(frame, found->box)) return r;
    pending_.reset();
    // The object turned: so does what it is recognised by.
    template_ = templ;
    lost_ = false;
    misses_ = 0;
    // Found the same way round it goes on as it went; turned, its old velocity is no guide.
    if (found->quarter_turns == 0)
        motion_.relocate(c, t);
    else
        motion_.reset(c, t);
    box_w_ = found->box.width();
    box_h_ = found->box.height();
    last_box_ = found->box;
    r.box = found->box;
    r.confidence = conf;
    r.lost = false;
    r.reacquired = true;
    return r;
}

void ObjectTracker::rescale(cv::Size to) {
    // A new picture size (the stream changed resolution): the same object, found again by
    // the search at its new scale.
    const double kx = static_cast<double>(to.width) / size_.width;
    const double ky = static_cast<double>(to.height) / size_.height;
    const Point c = motion_.predict(motion_.last_time());
    box_w_ *= kx;
    box_h_ *= ky;
    start_area_ *= kx * ky;
    last_box_ = last_box_.scaled(kx, ky);
    motion_.reset({c.x * kx, c.y * ky}, motion_.last_time());
    size_ = to;
    if (!lost_) {
        lost_ = true;
        lost_since_ = motion_.last_time();
    }
}

}  // namespace gimbal::track
