// Both eyes tracked independently and in parallel (one worker thread for the right eye).
#pragma once

#include "tracker/hand_tracker.hpp"

#include <memory>

namespace gc {

struct StereoEstimate {
    EyeEstimate left;
    EyeEstimate right;
};

class StereoHandTracker {
public:
    explicit StereoHandTracker(const TrackerParams& params = {});
    ~StereoHandTracker();

    // Tracks one stereo pair; the right eye's tracker is seeded differently from the left's
    // (derived from params.seed) so the two are independent but reproducible.
    StereoEstimate process(const cv::Mat& left_bgr, const cv::Mat& right_bgr, const ImageMotion& left_motion = {},
                           const ImageMotion& right_motion = {});
    void reset();
    const HandTracker& eye(Eye e) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc
