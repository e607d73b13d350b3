#include "track/redetect.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace gimbal::track {

cv::Mat turned(const cv::Mat& templ, int quarter_turns) {
    cv::Mat out;
    switch (quarter_turns % 4) {
        case 1:
            cv::rotate(templ, out, cv::ROTATE_90_CLOCKWISE);
            return out;
        case 2:
            cv::rotate(templ, out, cv::ROTATE_180);
            return out;
        case 3:
            cv::rotate(templ, out, cv::ROTATE_90_COUNTERCLOCKWISE);
            return out;
        default:
            return templ;
    }
}

std::optional<Candidate> search(const cv::Mat& frame, const SearchRequest& r) {
    if (r.templ == nullptr || r.templ->empty() || r.width <= 0 || r.height <= 0)
        return std::nullopt;
    const cv::Rect image(0, 0, frame.cols, frame.rows);
    const Box around = Box::around(r.predicted, r.width, r.height);
    const cv::Rect window = cv::Rect(static_cast<int>(std::floor(around.x0 - r.margin)),
                                     static_cast<int>(std::floor(around.y0 - r.margin)),
                                     static_cast<int>(std::ceil(around.width() + 2 * r.margin)),
                                     static_cast<int>(std::ceil(around.height() + 2 * r.margin))) &
                            image;
    if (window.area() <= 0) return std::nullopt;
    cv::Mat grey;
    if (frame.channels() == 3)
        cv::cvtColor(frame(window), grey, cv::COLOR_BGR2GRAY);
    else
        grey = frame(window);

    std::optional<Candidate> best;
    for (int q = 0; q < (r.turns ? 4 : 1); ++q) {
        const cv::Mat templ = turned(*r.templ, q);
        const bool across = q % 2 == 1;
        const double w = across ? r.height : r.width, h = across ? r.width : r.height;
        for (const double s : r.scales) {
            // Shrink the window so that the object at this scale is as large as the template.
            const double k = templ.cols / (w * s);
            const cv::Size size(static_cast<int>(std::lround(window.width * k)),
                                static_cast<int>(std::lround(window.height * k)));
            if (size.width < templ.cols || size.height < templ.rows) continue;
            cv::Mat small, small32, response;
            cv::resize(grey, small, size, 0, 0, k < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
            small.convertTo(small32, CV_32F);
            cv::matchTemplate(small32, templ, response, cv::TM_CCOEFF_NORMED);
            double max_value = 0;
            cv::Point max_at;
            cv::minMaxLoc(response, nullptr, &max_value, nullptr, &max_at);
            if (!std::isfinite(max_value) || (best && max_value <= best->score)) continue;
            const double x0 = window.x + max_at.x / k, y0 = window.y + max_at.y / k;
            best = Candidate{{x0, y0, x0 + w * s, y0 + h * s}, max_value, q};
        }
    }
    return best;
}

}  // namespace gimbal::track
