// The attended view: a digital pan/zoom over the left image that frames the hand and the
// region it points at, eased from frame to frame so that it does not jitter.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

namespace gc::gst {

class AttentionWindow {
public:
    // Per-frame easing towards the target (0 < rate <= 1): fast while tracking, slower
    // when zooming back out to the whole frame.
    static constexpr double kFollowRate = 0.2;
    static constexpr double kReleaseRate = 0.05;

    // The crop of a `frame`-sized image for this frame, with the aspect ratio `aspect`
    // (width / height) of the output; `eye` is the left view's estimate.
    cv::Rect update(cv::Size frame, double aspect, const EyeEstimate& eye);

    // Forget the smoothing: the next update starts from the target.
    void reset() { valid_ = false; }

private:
    cv::Rect2d window_;
    bool valid_ = false;
};

}  // namespace gc::gst
