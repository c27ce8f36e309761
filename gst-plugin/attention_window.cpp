#include "attention_window.hpp"

#include <algorithm>
#include <cmath>

namespace gc::gst {
namespace {

// The largest rectangle of aspect `aspect` centred in `frame`.
cv::Rect2d full_view(cv::Size frame, double aspect)
{
    double w = frame.width;
    double h = w / aspect;
    if (h > frame.height) {
        h = frame.height;
        w = h * aspect;
    }
    return {(frame.width - w) / 2.0, (frame.height - h) / 2.0, w, h};
}

cv::Rect2d hand_view(cv::Size frame, double aspect, const EyeEstimate& eye)
{
    // Centre between the fingertip and a point one hand-length further along the
    // pointing direction: the hand stays in view and the pointed-at region comes in.
    const cv::Point2d palm(eye.palm.x, eye.palm.y);
    const cv::Point2d tip(eye.fingertip.x, eye.fingertip.y);
    const cv::Point2d centre = tip + 0.5 * (tip - palm);
    // Zoom so the hand takes about a third of the width, never closer than a quarter of
    // the frame (too much zoom magnifies the tracker's jitter).
    const double hand = std::max({double(eye.bbox.width), double(eye.bbox.height) * aspect, 1.0});
    double w = std::clamp(3.0 * hand, frame.width / 4.0, double(frame.width));
    double h = w / aspect;
    if (h > frame.height) {
        h = frame.height;
        w = h * aspect;
    }
    return {centre.x - w / 2.0, centre.y - h / 2.0, w, h};
}

// The region's width across the view, centred on it.
cv::Rect2d region_view(cv::Size frame, double aspect, const cv::Rect2d& region)
{
    double w = std::clamp(region.width, 2.0, double(frame.width));
    double h = w / aspect;
    if (h > frame.height) {
        h = frame.height;
        w = h * aspect;
    }
    const cv::Point2d centre(region.x + region.width / 2.0, region.y + region.height / 2.0);
    return {centre.x - w / 2.0, centre.y - h / 2.0, w, h};
}

}  // namespace

cv::Rect AttentionWindow::update(cv::Size frame, double aspect, const EyeEstimate& eye,
                                 const std::optional<cv::Rect2d>& region)
{
    if (!(aspect > 0.0) || frame.width <= 0 || frame.height <= 0)
        return {0, 0, std::max(frame.width, 0), std::max(frame.height, 0)};
    const bool follow = eye.valid();
    const cv::Rect2d target = region   ? region_view(frame, aspect, *region)
                              : follow ? hand_view(frame, aspect, eye)
                                       : full_view(frame, aspect);
    if (!valid_) {
        window_ = target;
        valid_ = true;
    } else {
        const double rate = region ? kTargetRate : follow ? kFollowRate : kReleaseRate;
        window_.x += rate * (target.x - window_.x);
        window_.y += rate * (target.y - window_.y);
        window_.width += rate * (target.width - window_.width);
        window_.height += rate * (target.height - window_.height);
    }
    // Keep the window inside the frame by sliding it, not by shrinking it.
    cv::Rect2d r = window_;
    r.width = std::clamp(r.width, 2.0, double(frame.width));
    r.height = std::clamp(r.height, 2.0, double(frame.height));
    r.x = std::clamp(r.x, 0.0, frame.width - r.width);
    r.y = std::clamp(r.y, 0.0, frame.height - r.height);
    window_ = r;
    cv::Rect out(int(std::lround(r.x)), int(std::lround(r.y)), int(std::lround(r.width)), int(std::lround(r.height)));
    return out & cv::Rect(0, 0, frame.width, frame.height);
}

}  // namespace gc::gst
