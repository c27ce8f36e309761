#include "detect/hand_finder.hpp"

#include "detect/hand_landmarks.hpp"
#include "detect/model_files.hpp"
#include "detect/palm_detector.hpp"

#include <cmath>

namespace gc {

namespace {

// Palms tried, best first, before a frame is said to hold no hand: a second one catches a
// best box that sat on a hand-coloured distraction.
constexpr std::size_t kPalmsTried = 2;

FoundHand found(const HandKeyPoints& h) { return FoundHand{h.points, h.presence, classify_gesture(h)}; }

}  // namespace

cv::Point2f palm_centre(const std::array<cv::Point2f, 21>& p) { return (p[0] + p[5] + p[9] + p[13] + p[17]) * 0.2f; }

struct HandFinder::Impl {
    HandFinderParams params;
    PalmDetector palms;
    LandmarkModel landmarks;
    int palm_calls = 0;
    int landmark_calls = 0;

    explicit Impl(const HandFinderParams& p)
        : params(p), palms(find_model(kPalmModelFile, p.model_dir)),
          landmarks(find_model(kLandmarkModelFile, p.model_dir))
    {
    }

    std::optional<FoundHand> confirmed(const cv::Mat& bgr, const HandCrop& crop)
    {
        ++landmark_calls;
        const HandKeyPoints hand = landmarks.run(bgr, crop);
        if (hand.presence < params.min_presence) return std::nullopt;
        return found(hand);
    }
};

HandFinder::HandFinder(const HandFinderParams& params) : impl_(std::make_unique<Impl>(params)) {}
HandFinder::~HandFinder() = default;
HandFinder::HandFinder(HandFinder&&) noexcept = default;
HandFinder& HandFinder::operator=(HandFinder&&) noexcept = default;

std::optional<FoundHand> HandFinder::find(const cv::Mat& bgr)
{
    ++impl_->palm_calls;
    const std::vector<PalmDetection> palms = impl_->palms.detect(bgr, impl_->params.min_palm_score);
    for (std::size_t i = 0; i < std::min(palms.size(), kPalmsTried); ++i)
        if (auto hand = impl_->confirmed(bgr, crop_from_palm(palms[i]))) return hand;
    return std::nullopt;
}

std::optional<FoundHand> HandFinder::follow(const cv::Mat& bgr, const std::array<cv::Point2f, 21>& around)
{
    HandKeyPoints known;
    known.points = around;
    return impl_->confirmed(bgr, crop_from_landmarks(known));
}

// The crop a pointing hand fills: centred a little towards the finger, 2.5 palm-to-tip
// lengths wide, turned so that the finger points up.
std::optional<FoundHand> HandFinder::confirm(const cv::Mat& bgr, cv::Point2f palm, cv::Point2f fingertip)
{
    const cv::Point2f reach = fingertip - palm;
    const float length = std::hypot(reach.x, reach.y);
    if (!(length > 4.0f)) return std::nullopt;
    const HandCrop crop{palm + 0.3f * reach, 2.5f * length, std::atan2(reach.x, -reach.y)};
    return impl_->confirmed(bgr, crop);
}

int HandFinder::palm_calls() const { return impl_->palm_calls; }
int HandFinder::landmark_calls() const { return impl_->landmark_calls; }

}  // namespace gc
