#include "detect/gesture.hpp"

#include <algorithm>

namespace gc {

namespace {

// How much farther from the wrist than its PIP an extended finger's tip lies: between the
// ratios of extended and curled fingers on the reference hands (docs/adr/0020).
constexpr float kExtendedReach = 1.1f;

}  // namespace

std::array<bool, 4> extended_fingers(const HandKeyPoints& hand)
{
    const HandPoint joints[4][2] = {{HandPoint::IndexPip, HandPoint::IndexTip},
                                    {HandPoint::MiddlePip, HandPoint::MiddleTip},
                                    {HandPoint::RingPip, HandPoint::RingTip},
                                    {HandPoint::PinkyPip, HandPoint::PinkyTip}};
    const cv::Point2f wrist = hand.point(HandPoint::Wrist);
    std::array<bool, 4> extended{};
    for (int f = 0; f < 4; ++f) {
        const float pip = float(cv::norm(hand.point(joints[f][0]) - wrist));
        const float tip = float(cv::norm(hand.point(joints[f][1]) - wrist));
        extended[f] = tip > kExtendedReach * pip;
    }
    return extended;
}

Gesture classify_gesture(const HandKeyPoints& hand)
{
    const std::array<bool, 4> e = extended_fingers(hand);
    const int count = int(std::count(e.begin(), e.end(), true));
    if (count == 0) return Gesture::Fist;
    if (count == 4) return Gesture::Open;
    if (count == 1 && e[0]) return Gesture::Pointing;
    return Gesture::Other;
}

}  // namespace gc
