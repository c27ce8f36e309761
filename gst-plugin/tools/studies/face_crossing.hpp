// The face-crossing criterion of face_pass, shared by the face-crossing test and the
// tracking study so that the study's figures measure what the test asserts.
#pragma once

#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>

namespace gc_test {

// The hand covers at least 5 % of the face's skin (false without a face).
inline bool hand_crosses_face(const gc::sim::EyeTruth& truth)
{
    const int hand = cv::countNonZero(truth.mask);
    return !truth.face.empty() && hand > 0 && cv::countNonZero(truth.mask & truth.face) >= 0.05 * hand;
}

// The tracker is on the hand: tracking, its filled contour (`tracked`) at IoU >= 0.5.
inline bool on_the_hand(const gc::EyeEstimate& e, const gc::sim::EyeTruth& truth, const cv::Mat1b& tracked)
{
    return e.valid() && gc::mask_iou(truth.mask, tracked) >= 0.5;
}

}  // namespace gc_test
