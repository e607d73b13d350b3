// A synthetic picture for the tracker's tests and benchmark: textured ground (blurred noise in
// earthy colours, a road), a band of sky at the top, a shaded vehicle-like shape (body, darker
// cabin, windscreen, shadow) driving along a polyline at constant speed, and optionally a
// bridge (an opaque textured band) it passes under. Rendered with OpenCV; every frame is a
// pure function of its time (a fixed seed for the textures, per-frame sensor noise seeded by
// the frame's time), and the vehicle's true box is known.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

namespace track_test {

struct SceneOptions {
    int width = 640;
    int height = 360;
    int sky_rows = 60;           // rows of sky at the top
    cv::Size2d vehicle{34, 16};  // length along the heading, width across (pixels)
    double speed_px_s = 60;      // along the route
    std::vector<cv::Point2d> route{{60, 250}, {580, 250}};
    double corner_radius = 40;         // the route's corners are arcs of this radius
    std::optional<cv::Rect2d> bridge;  // an opaque band drawn over the vehicle
    double noise_sigma = 2.0;          // sensor noise per pixel and frame
};

class SyntheticScene {
  public:
    explicit SyntheticScene(SceneOptions options = {}) : o_(std::move(options)) {
        build_path();
        build();
    }

    const SceneOptions& options() const { return o_; }

    // Where the vehicle is at time t (it stops at the end of the route) and where it heads.
    cv::Point2d position(double t) const { return pose(t).first; }
    double heading_rad(double t) const { return pose(t).second; }

    // The vehicle's axis-aligned bounding box at time t (its rotated body's extent).
    cv::Rect2d truth(double t) const {
        cv::Point2f corners[4];
        body(t).points(corners);
        float x0 = corners[0].x, x1 = x0, y0 = corners[0].y, y1 = y0;
        for (const auto& c : corners) {
            x0 = std::min(x0, c.x);
            x1 = std::max(x1, c.x);
            y0 = std::min(y0, c.y);
            y1 = std::max(y1, c.y);
        }
        return {x0, y0, x1 - x0, y1 - y0};
    }

    // Whether (x, y) lies on the vehicle's body at time t, `margin` pixels around it included.
    bool on_vehicle(double x, double y, double t, double margin = 2) const {
        const auto [centre, heading] = pose(t);
        const double dx = x - centre.x, dy = y - centre.y;
        const double along = dx * std::cos(heading) + dy * std::sin(heading);
        const double across = -dx * std::sin(heading) + dy * std::cos(heading);
        return std::abs(along) <= o_.vehicle.width / 2 + margin &&
               std::abs(across) <= o_.vehicle.height / 2 + margin;
    }

    // The fraction of the vehicle's box the bridge covers at time t.
    double occluded_fraction(double t) const {
        if (!o_.bridge) return 0;
        const auto box = truth(t);
        return (box & *o_.bridge).area() / std::max(1.0, box.area());
    }

    // The picture at time t, BGR.
    cv::Mat render(double t) const {
        cv::Mat frame = background_.clone();
        draw_vehicle(frame, t);
        if (o_.bridge) {
            const cv::Rect r = to_int(*o_.bridge) & cv::Rect(0, 0, o_.width, o_.height);
            bridge_(cv::Rect(0, 0, r.width, r.height)).copyTo(frame(r));
        }
        if (o_.noise_sigma > 0) {
            cv::Mat noise(frame.size(), CV_16SC3);
            cv::RNG rng(static_cast<std::uint64_t>(std::llround(t * 1000)) + 1);
            rng.fill(noise, cv::RNG::NORMAL, 0, o_.noise_sigma);
            cv::Mat wide;
            frame.convertTo(wide, CV_16SC3);
            wide += noise;
            wide.convertTo(frame, CV_8UC3);
        }
        return frame;
    }

    // The picture at time t in grey.
    cv::Mat render_gray(double t) const {
        cv::Mat gray;
        cv::cvtColor(render(t), gray, cv::COLOR_BGR2GRAY);
        return gray;
    }

  private:
    static cv::Rect to_int(const cv::Rect2d& r) {
        return {static_cast<int>(std::lround(r.x)), static_cast<int>(std::lround(r.y)),
                static_cast<int>(std::lround(r.width)), static_cast<int>(std::lround(r.height))};
    }

    // Noise at 1/scale of the size, smoothly enlarged: blotches of that size.
    static cv::Mat blotches(cv::RNG& rng, cv::Size size, int scale, double amplitude) {
        cv::Mat small(std::max(2, size.height / scale), std::max(2, size.width / scale), CV_32F);
        rng.fill(small, cv::RNG::UNIFORM, -amplitude, amplitude);
        cv::Mat big;
        cv::resize(small, big, size, 0, 0, cv::INTER_CUBIC);
        return big;
    }

    void build() {
        const cv::Size size(o_.width, o_.height);
        cv::RNG rng(27);
        // Ground: an earthy base with fields (large blotches), clumps and fine grain.
        cv::Mat shade =
            blotches(rng, size, 48, 22) + blotches(rng, size, 12, 12) + blotches(rng, size, 3, 7);
        cv::Mat base(size, CV_32FC3, cv::Scalar(70, 112, 104));  // B, G, R: olive ground
        std::vector<cv::Mat> channels;
        cv::split(base, channels);
        channels[0] += shade * 0.7;
        channels[1] += shade;
        channels[2] += shade * 0.9;
        cv::merge(channels, base);
        base.convertTo(background_, CV_8UC3);
        // A road along the route.
        for (std::size_t i = 0; i + 1 < path_.size(); i += 8)
            cv::line(background_, path_[i], path_[std::min(i + 8, path_.size() - 1)],
                     cv::Scalar(92, 94, 96), static_cast<int>(o_.vehicle.height * 1.8),
                     cv::LINE_AA);
        // Sky: a smooth gradient, lighter towards the horizon.
        for (int y = 0; y < std::min(o_.sky_rows, o_.height); ++y) {
            const double k = static_cast<double>(y) / std::max(1, o_.sky_rows);
            background_.row(y).setTo(cv::Scalar(215 + 20 * k, 170 + 40 * k, 120 + 60 * k));
        }
        if (o_.bridge) {
            // Concrete with stains and two dark parapet lines.
            const cv::Size b(static_cast<int>(std::lround(o_.bridge->width)),
                             static_cast<int>(std::lround(o_.bridge->height)));
            cv::Mat deck = blotches(rng, b, 6, 14) + cv::Scalar(150);
            deck.convertTo(deck, CV_8U);
            cv::cvtColor(deck, bridge_, cv::COLOR_GRAY2BGR);
            cv::rectangle(bridge_, {0, 0, 3, b.height}, cv::Scalar(60, 60, 60), cv::FILLED);
            cv::rectangle(bridge_, {b.width - 3, 0, 3, b.height}, cv::Scalar(60, 60, 60),
                          cv::FILLED);
        }
    }

    std::pair<cv::Point2d, double> pose(double t) const {
        // The dense path is sampled every path_step pixels; interpolate between samples.
        const double s = std::max(0.0, t) * o_.speed_px_s / path_step;
        const auto i = std::min(static_cast<std::size_t>(s), path_.size() - 1);
        const auto j = std::min(i + 1, path_.size() - 1);
        const double k = std::min(1.0, s - static_cast<double>(i));
        const cv::Point2d p = path_[i] + k * (path_[j] - path_[i]);
        const std::size_t a = i + 1 < path_.size() ? i : (i > 0 ? i - 1 : 0);
        const std::size_t b = std::min(a + 1, path_.size() - 1);
        const cv::Point2d d = path_[b] - path_[a];
        return {p, b == a ? 0.0 : std::atan2(d.y, d.x)};
    }

    // The route with its corners rounded, as points path_step apart.
    void build_path() {
        std::vector<cv::Point2d> smooth;  // the route with each corner replaced by an arc
        const auto& r = o_.route;
        smooth.push_back(r.front());
        for (std::size_t i = 1; i + 1 < r.size(); ++i) {
            const cv::Point2d in = r[i] - r[i - 1], out = r[i + 1] - r[i];
            const double lin = std::hypot(in.x, in.y), lout = std::hypot(out.x, out.y);
            const cv::Point2d u = in / lin, v = out / lout;
            const double turn = std::acos(std::clamp(u.dot(v), -1.0, 1.0));
            const double cut = std::min({o_.corner_radius * std::tan(turn / 2), lin / 2, lout / 2});
            const cv::Point2d a = r[i] - cut * u, b = r[i] + cut * v;
            for (int n = 0; n <= 16;
                 ++n) {  // a quadratic Bezier through the corner: close to an arc
                const double q = n / 16.0;
                smooth.push_back((1 - q) * (1 - q) * a + 2 * q * (1 - q) * r[i] + q * q * b);
            }
        }
        smooth.push_back(r.back());
        path_.assign(1, smooth.front());
        double carried = 0;
        for (std::size_t i = 1; i < smooth.size(); ++i) {
            const cv::Point2d d = smooth[i] - smooth[i - 1];
            const double length = std::hypot(d.x, d.y);
            double at = path_step - carried;
            for (; at <= length; at += path_step)
                path_.push_back(smooth[i - 1] + (at / length) * d);
            carried = length - (at - path_step);
        }
    }

    cv::RotatedRect body(double t, double grow = 1.0) const {
        const auto [centre, heading] = pose(t);
        return {cv::Point2f(static_cast<float>(centre.x), static_cast<float>(centre.y)),
                cv::Size2f(static_cast<float>(o_.vehicle.width * grow),
                           static_cast<float>(o_.vehicle.height * grow)),
                static_cast<float>(heading * 180 / CV_PI)};
    }

    static void fill(cv::Mat& frame, const cv::RotatedRect& r, const cv::Scalar& colour) {
        cv::Point2f p[4];
        r.points(p);
        constexpr int shift = 4;  // sub-pixel corners
        std::vector<cv::Point> q;
        for (const auto& c : p)
            q.emplace_back(static_cast<int>(std::lround(c.x * (1 << shift))),
                           static_cast<int>(std::lround(c.y * (1 << shift))));
        cv::fillConvexPoly(frame, q, colour, cv::LINE_AA, shift);
    }

    void draw_vehicle(cv::Mat& frame, double t) const {
        const auto [centre, heading] = pose(t);
        const cv::Point2d ahead(std::cos(heading), std::sin(heading));
        const cv::Point2d side(-ahead.y, ahead.x);
        const double length = o_.vehicle.width;
        const double width = o_.vehicle.height;
        auto part = [&](double along, double across, double l, double w) {
            const cv::Point2d c = centre + along * length * ahead + across * width * side;
            return cv::RotatedRect(
                cv::Point2f(static_cast<float>(c.x), static_cast<float>(c.y)),
                cv::Size2f(static_cast<float>(l * length), static_cast<float>(w * width)),
                static_cast<float>(heading * 180 / CV_PI));
        };
        fill(frame, part(0.08, 0.25, 1.0, 1.0), cv::Scalar(40, 48, 46));   // shadow
        fill(frame, part(0, 0, 1.0, 1.0), cv::Scalar(40, 40, 200));        // red body
        fill(frame, part(0, 0.3, 1.0, 0.25), cv::Scalar(30, 30, 150));     // shaded flank
        fill(frame, part(-0.05, 0, 0.45, 0.7), cv::Scalar(60, 50, 110));   // cabin roof
        fill(frame, part(0.2, 0, 0.1, 0.7), cv::Scalar(50, 30, 20));       // windscreen
        fill(frame, part(0.42, 0, 0.08, 0.8), cv::Scalar(200, 220, 230));  // bumper
    }

    static constexpr double path_step = 0.5;

    SceneOptions o_;
    std::vector<cv::Point2d> path_;
    cv::Mat background_;
    cv::Mat bridge_;
};

}  // namespace track_test
