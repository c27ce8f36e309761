#include "tracker/key_point_flow.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cfloat>

namespace gc {

namespace {

const cv::Size kWindow(21, 21);
constexpr int kLevels = 3;
// A point is kept only if following it back lands within this many pixels of its start:
// a point that slid along an edge or onto the background does not come back.
constexpr float kMaxRoundTrip = 1.0f;
// The pyramids' region reaches this far past the points: the window at the coarsest level
// plus a fast hand's move between two frames.
constexpr int kMargin = 192;
// A region serves while every point lies at least this far inside its edges (or the
// frame's, where they coincide).
constexpr int kInner = 112;
// Region corners on the coarsest level's grid: each level then samples the pixels the
// whole frame's pyramid would.
constexpr int kAlign = 1 << kLevels;

void build(const cv::Mat1b& grey, const cv::Rect& area, std::vector<cv::Mat>& pyramid)
{
    cv::buildOpticalFlowPyramid(grey(area), pyramid, kWindow, kLevels, true, cv::BORDER_REFLECT_101,
                                cv::BORDER_CONSTANT, false);
}

cv::Rect around(const KeyPointFlow::Points& points, const cv::Size& frame)
{
    float x0 = points[0].x, y0 = points[0].y, x1 = x0, y1 = y0;
    for (const cv::Point2f& p : points) {
        x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
        x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
    const cv::Rect whole(0, 0, frame.width, frame.height);
    if (!(x1 - x0 < frame.width && y1 - y0 < frame.height)) return whole;  // also NaN
    const int left = std::max(0, cvFloor(x0) - kMargin) / kAlign * kAlign;
    const int top = std::max(0, cvFloor(y0) - kMargin) / kAlign * kAlign;
    const cv::Rect area = cv::Rect(cv::Point(left, top), cv::Point(cvCeil(x1) + kMargin, cvCeil(y1) + kMargin)) & whole;
    return area.width > kWindow.width && area.height > kWindow.height ? area : whole;
}

bool well_inside(const KeyPointFlow::Points& points, const cv::Rect& area, const cv::Size& frame)
{
    const float left = area.x > 0 ? float(area.x + kInner) : -FLT_MAX;
    const float top = area.y > 0 ? float(area.y + kInner) : -FLT_MAX;
    const float right = area.br().x < frame.width ? float(area.br().x - kInner) : FLT_MAX;
    const float bottom = area.br().y < frame.height ? float(area.br().y - kInner) : FLT_MAX;
    return std::all_of(points.begin(), points.end(), [&](const cv::Point2f& p) {
        return p.x >= left && p.x <= right && p.y >= top && p.y <= bottom;
    });
}

}  // namespace

void KeyPointFlow::place_area(const cv::Size& frame)
{
    if (well_inside(kept_, area_, frame) && (area_ & cv::Rect(cv::Point(), frame)) == area_) return;
    area_ = around(kept_, frame);
    build(grey_, area_, previous_);
}

void KeyPointFlow::keep(const cv::Mat& bgr, const Points& points)
{
    cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
    kept_ = points;
    area_ = around(kept_, grey_.size());
    build(grey_, area_, previous_);
    ready_ = true;
}

void KeyPointFlow::carry(const cv::Mat& bgr, Points& points, std::array<bool, kPoints>& moved)
{
    moved.fill(false);
    cv::cvtColor(bgr, next_grey_, cv::COLOR_BGR2GRAY);
    place_area(next_grey_.size());
    build(next_grey_, area_, current_);
    const cv::Point2f origin(area_.tl());
    from_.resize(kPoints);
    for (std::size_t i = 0; i < kPoints; ++i) from_[i] = kept_[i] - origin;
    const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.03);
    cv::calcOpticalFlowPyrLK(previous_, current_, from_, to_, status_, error_, kWindow, kLevels, stop);
    back_ = to_;
    cv::calcOpticalFlowPyrLK(current_, previous_, to_, back_, back_status_, error_, kWindow, kLevels, stop,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    for (std::size_t i = 0; i < kPoints; ++i) {
        if (!status_[i] || !back_status_[i] || cv::norm(back_[i] - from_[i]) > kMaxRoundTrip) continue;
        points[i] = to_[i] + origin;
        moved[i] = true;
    }
    std::swap(previous_, current_);
    std::swap(grey_, next_grey_);
    kept_ = points;
}

}  // namespace gc
