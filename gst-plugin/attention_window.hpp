// The attended view: a digital pan/zoom over the left image that frames the hand and the
// region it points at, or a target a held pointing picked, eased from frame to frame so that
// it does not jitter.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

#include <optional>

namespace gc::gst {

class AttentionWindow {
public:
    // Per-frame easing towards the target (0 < rate <= 1): fast while tracking, slower
    // when zooming back out to the whole frame.
    static constexpr double kFollowRate = 0.2;
    static constexpr double kReleaseRate = 0.05;
    // Towards a picked target: most of the way within half a second at 30 frames/s.
    static constexpr double kTargetRate = 0.25;

    // The crop of a `frame`-sized image for this frame, with the aspect ratio `aspect`
    // (width / height) of the output; `eye` is the left view's estimate. `target`, when
    // given, is the region to frame instead (its centre and width count).
    cv::Rect update(cv::Size frame, double aspect, const EyeEstimate& eye,
                    const std::optional<cv::Rect2d>& target = std::nullopt);

    // Forget the smoothing: the next update starts from the target.
    void reset() { valid_ = false; }

private:
    cv::Rect2d window_;
    bool valid_ = false;
};

}  // namespace gc::gst
