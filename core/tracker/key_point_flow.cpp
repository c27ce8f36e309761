#include "tracker/key_point_flow.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>

namespace gc {

namespace {

const cv::Size kWindow(21, 21);
constexpr int kLevels = 3;
// A point is kept only if following it back lands within this many pixels of its start:
// a point that slid along an edge or onto the background does not come back.
constexpr float kMaxRoundTrip = 1.0f;

}  // namespace

void KeyPointFlow::build(const cv::Mat& bgr, std::vector<cv::Mat>& pyramid)
{
    cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
    cv::buildOpticalFlowPyramid(grey_, pyramid, kWindow, kLevels, true, cv::BORDER_REFLECT_101, cv::BORDER_CONSTANT,
                                false);
}

void KeyPointFlow::keep(const cv::Mat& bgr, const Points& points)
{
    build(bgr, previous_);
    kept_ = points;
    ready_ = true;
}

void KeyPointFlow::carry(const cv::Mat& bgr, Points& points, std::array<bool, kPoints>& moved)
{
    moved.fill(false);
    build(bgr, current_);
    from_.assign(kept_.begin(), kept_.end());
    const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.03);
    cv::calcOpticalFlowPyrLK(previous_, current_, from_, to_, status_, error_, kWindow, kLevels, stop);
    back_ = to_;
    cv::calcOpticalFlowPyrLK(current_, previous_, to_, back_, back_status_, error_, kWindow, kLevels, stop,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    for (std::size_t i = 0; i < kPoints; ++i) {
        if (!status_[i] || !back_status_[i] || cv::norm(back_[i] - from_[i]) > kMaxRoundTrip) continue;
        points[i] = to_[i];
        moved[i] = true;
    }
    std::swap(previous_, current_);
    kept_ = points;
}

}  // namespace gc
