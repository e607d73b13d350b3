#include "track/appearance.hpp"

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace gimbal::track {

namespace {

cv::Rect integer_rect(const Box& b) {
    const int x0 = static_cast<int>(std::floor(b.x0));
    const int y0 = static_cast<int>(std::floor(b.y0));
    const int x1 = static_cast<int>(std::ceil(b.x1));
    const int y1 = static_cast<int>(std::ceil(b.y1));
    return {x0, y0, std::max(1, x1 - x0), std::max(1, y1 - y0)};
}

constexpr std::size_t luma_at = 64;  // the luma part's first bin

// A pixel's colour bin (4 levels per channel; 16 grey levels for grey frames) and luma bin
// (16 levels).
template <int Channels>
std::size_t colour_bin(const std::uint8_t* p) {
    if constexpr (Channels == 3)
        return static_cast<std::size_t>((p[0] >> 6) | ((p[1] >> 6) << 2) | ((p[2] >> 6) << 4));
    return static_cast<std::size_t>(p[0] >> 4);
}
template <int Channels>
std::size_t luma_bin(const std::uint8_t* p) {
    if constexpr (Channels == 3)
        return luma_at + static_cast<std::size_t>((p[0] * 29 + p[1] * 150 + p[2] * 77) >> 12);
    return luma_at + static_cast<std::size_t>(p[0] >> 4);
}

// The histograms of the pixels of `outer` inside `inner` and outside it (the ring).
template <int Channels>
void histograms(const cv::Mat& frame, const cv::Rect& inner, const cv::Rect& outer, Histogram& in,
                Histogram* ring) {
    in.fill(0);
    if (ring) ring->fill(0);
    double n_in = 0, n_ring = 0;
    for (int y = outer.y; y < outer.y + outer.height; ++y) {
        const std::uint8_t* row = frame.ptr<std::uint8_t>(y);
        for (int x = outer.x; x < outer.x + outer.width; ++x) {
            const std::uint8_t* p = row + x * Channels;
            Histogram* h = inner.contains({x, y}) ? &in : ring;
            if (!h) continue;
            (*h)[colour_bin<Channels>(p)] += 1;
            (*h)[luma_bin<Channels>(p)] += 1;
            (h == &in ? n_in : n_ring) += 1;
        }
    }
    if (n_in > 0)
        for (double& v : in) v /= n_in;
    if (ring && n_ring > 0)
        for (double& v : *ring) v /= n_ring;
}

void histograms(const cv::Mat& frame, const cv::Rect& inner, const cv::Rect& outer, Histogram& in,
                Histogram* ring) {
    if (frame.channels() == 3)
        histograms<3>(frame, inner, outer, in, ring);
    else
        histograms<1>(frame, inner, outer, in, ring);
}

bool histogram_frame(const cv::Mat& frame) {
    return !frame.empty() && frame.depth() == CV_8U &&
           (frame.channels() == 1 || frame.channels() == 3);
}

}  // namespace

cv::Size patch_size(const Box& box, int long_side) {
    const double w = std::max(1e-6, box.width()), h = std::max(1e-6, box.height());
    const double k = long_side / std::max(w, h);
    return {std::max(4, static_cast<int>(std::lround(w * k))),
            std::max(4, static_cast<int>(std::lround(h * k)))};
}

cv::Mat grey_patch(const cv::Mat& frame, const Box& box, cv::Size size) {
    const cv::Rect want = integer_rect(box);
    const cv::Rect have = want & cv::Rect(0, 0, frame.cols, frame.rows);
    cv::Mat grey;
    if (have.area() <= 0) return cv::Mat(size, CV_32F, cv::Scalar(0));
    cv::Mat part = frame(have);
    if (frame.channels() == 3)
        cv::cvtColor(part, grey, cv::COLOR_BGR2GRAY);
    else
        grey = part;
    if (have != want) {
        cv::Mat padded;
        cv::copyMakeBorder(grey, padded, have.y - want.y, want.br().y - have.br().y,
                           have.x - want.x, want.br().x - have.br().x, cv::BORDER_REPLICATE);
        grey = padded;
    }
    cv::Mat resized;
    cv::resize(grey, resized, size, 0, 0, cv::INTER_AREA);
    cv::Mat out;
    resized.convertTo(out, CV_32F);
    return out;
}

double ncc(const cv::Mat& a, const cv::Mat& b) {
    if (a.size() != b.size() || a.empty()) return 0;
    cv::Scalar ma, sa, mb, sb;
    cv::meanStdDev(a, ma, sa);
    cv::meanStdDev(b, mb, sb);
    if (sa[0] < flat_sigma || sb[0] < flat_sigma) return 0;
    const double n = static_cast<double>(a.total());
    const double cross = (a - ma[0]).dot(b - mb[0]) / n;
    return std::clamp(cross / (sa[0] * sb[0]), -1.0, 1.0);
}

double structure(const cv::Mat& patch) {
    if (patch.empty()) return 0;
    cv::Mat blurred;
    cv::GaussianBlur(patch, blurred, {0, 0}, 1.5, 1.5, cv::BORDER_REPLICATE);
    cv::Scalar mean, sigma;
    cv::meanStdDev(patch - blurred, mean, sigma);
    return sigma[0];
}

Histogram colour_histogram(const cv::Mat& frame, const Box& box) {
    Histogram h{};
    if (!histogram_frame(frame) || !box.valid()) return h;
    const cv::Rect inner = integer_rect(box) & cv::Rect(0, 0, frame.cols, frame.rows);
    if (inner.area() > 0) histograms(frame, inner, inner, h, nullptr);
    return h;
}

double similarity(const Histogram& a, const Histogram& b) {
    double colour = 0, luma = 0;
    for (std::size_t i = 0; i < luma_at; ++i) colour += std::sqrt(a[i] * b[i]);
    for (std::size_t i = luma_at; i < a.size(); ++i) luma += std::sqrt(a[i] * b[i]);
    return std::clamp(std::min(colour, luma), 0.0, 1.0);
}

double distinctness(const cv::Mat& frame, const Box& box) {
    if (!histogram_frame(frame) || !box.valid()) return 0;
    const cv::Rect image(0, 0, frame.cols, frame.rows);
    const cv::Rect inner = integer_rect(box) & image;
    const double mx = std::max(4.0, box.width() / 2), my = std::max(4.0, box.height() / 2);
    const cv::Rect outer =
        integer_rect({box.x0 - mx, box.y0 - my, box.x1 + mx, box.y1 + my}) & image;
    if (inner.area() <= 0 || outer.area() <= inner.area()) return 0;
    Histogram in{}, ring{};
    histograms(frame, inner, outer, in, &ring);
    return std::sqrt(std::max(0.0, 1 - similarity(in, ring)));
}

}  // namespace gimbal::track
