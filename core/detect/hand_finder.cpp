#include "detect/hand_finder.hpp"

#include "detect/hand_landmarks.hpp"
#include "detect/model_files.hpp"
#include "detect/palm_detector.hpp"

#include <algorithm>
#include <cmath>

namespace gc {

namespace {

// Palms tried, best first, before a frame is said to hold no hand: the ones after the first
// catch a hand whose box scored below boxes on hand-coloured distractions (docs/adr/0028).
constexpr std::size_t kPalmsTried = 3;

// How far, in palm sizes (wrist to middle knuckle), the key points of a found hand may move
// on average when the landmark model looks again through the crop they give, and how many
// such looks they have to settle. At the better of two looks, 0.25 passed 52 of 54 real palm
// detections, 213 of 235 rendered hands and 32 of 80 rendered decoys; a third look lets
// more hands through and the moving-hand watch catches the decoys that pass.
constexpr double kSettledMove = 0.25;
constexpr int kSettlingLooks = 3;
// A palm whose key points settle within this many palm sizes is taken at once; one that
// settles less well is taken only if no other palm tried settles better. A shelf the
// models take for a hand settled at 0.25 where the rendered hand beside it did at 0.06.
constexpr double kSurelySettled = 0.1;

FoundHand found(const HandKeyPoints& h) { return FoundHand{h.points, h.presence, classify_gesture(h)}; }

// A found hand and how far its key points moved on the look that settled them, in palm sizes.
struct SettledHand {
    FoundHand hand;
    double move = 0.0;
};

}  // namespace

cv::Point2f palm_centre(const std::array<cv::Point2f, 21>& p) { return (p[0] + p[5] + p[9] + p[13] + p[17]) * 0.2f; }

double key_point_move(const std::array<cv::Point2f, 21>& from, const std::array<cv::Point2f, 21>& to)
{
    double moved = 0.0;
    for (std::size_t i = 0; i < to.size(); ++i) moved += cv::norm(from[i] - to[i]);
    return moved / (double(to.size()) * std::max(1.0, cv::norm(to[9] - to[0])));
}

struct HandFinder::Impl {
    HandFinderParams params;
    PalmDetector palms;
    LandmarkModel landmarks;

    explicit Impl(const HandFinderParams& p)
        : params(p), palms(find_model(kPalmModelFile, p.model_dir)),
          landmarks(find_model(kLandmarkModelFile, p.model_dir))
    {
    }

    std::optional<HandKeyPoints> run(const cv::Mat& bgr, const HandCrop& crop)
    {
        if (!crop.usable()) return std::nullopt;  // shows no hand: the model is not asked
        HandKeyPoints hand = landmarks.run(bgr, crop);
        if (hand.presence < params.min_presence) return std::nullopt;
        return hand;
    }

    std::optional<FoundHand> confirmed(const cv::Mat& bgr, const HandCrop& crop)
    {
        const std::optional<HandKeyPoints> hand = run(bgr, crop);
        if (!hand) return std::nullopt;
        return found(*hand);
    }

    // A hand found from a guessed crop (a palm box, a blob) is looked at again through the
    // crop its own key points give, up to three times: a hand's key points settle, while on a
    // hand-coloured object they scatter anew with each look. The first look's key points
    // are returned: on the real pair they made the better template (3D coverage 98.5 %
    // against 92 % with the settled ones), with the move of the look that settled.
    std::optional<SettledHand> settled(const cv::Mat& bgr, const HandCrop& crop)
    {
        const std::optional<HandKeyPoints> first = run(bgr, crop);
        std::optional<HandKeyPoints> last = first;
        for (int look = 0; last && look < kSettlingLooks; ++look) {
            const std::optional<HandKeyPoints> next = run(bgr, crop_from_landmarks(*last));
            const double move = next ? key_point_move(last->points, next->points) : 0.0;
            if (next && move <= kSettledMove) return SettledHand{found(*first), move};
            last = next;
        }
        return std::nullopt;
    }
};

HandFinder::HandFinder(const HandFinderParams& params) : impl_(std::make_unique<Impl>(params)) {}
HandFinder::~HandFinder() = default;
HandFinder::HandFinder(HandFinder&&) noexcept = default;
HandFinder& HandFinder::operator=(HandFinder&&) noexcept = default;

std::optional<FoundHand> HandFinder::find(const cv::Mat& bgr)
{
    return find_in(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows));
}

std::optional<FoundHand> HandFinder::find_in(const cv::Mat& bgr, const cv::Rect& region)
{
    const cv::Rect inside = region & cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (inside.empty()) return std::nullopt;
    std::vector<PalmDetection> palms = impl_->palms.detect(bgr(inside), impl_->params.min_palm_score);
    const cv::Point2f offset(inside.tl());
    std::optional<SettledHand> best;
    for (std::size_t i = 0; i < std::min(palms.size(), kPalmsTried); ++i) {
        PalmDetection& palm = palms[i];
        palm.box += offset;
        for (cv::Point2f& p : palm.points) p += offset;
        // The landmark model looks at the whole frame: a crop may reach beyond the region.
        const std::optional<SettledHand> hand = impl_->settled(bgr, crop_from_palm(palm));
        if (!hand || (best && hand->move >= best->move)) continue;
        best = hand;
        if (hand->move <= kSurelySettled) break;
    }
    if (!best) return std::nullopt;
    return best->hand;
}

std::optional<FoundHand> HandFinder::follow(const cv::Mat& bgr, const std::array<cv::Point2f, 21>& around,
                                            double look_again_beyond)
{
    HandKeyPoints known;
    known.points = around;
    std::optional<FoundHand> first = impl_->confirmed(bgr, crop_from_landmarks(known));
    const double moved = first ? key_point_move(around, first->points) : 0.0;
    if (!first || !(moved >= look_again_beyond)) return first;
    // A second look that wanders on is sliding onto something else, such as a face behind the hand.
    known.points = first->points;
    std::optional<FoundHand> again = impl_->confirmed(bgr, crop_from_landmarks(known));
    return again && key_point_move(first->points, again->points) < moved ? again : first;
}

// The crop a pointing hand fills: centred a little towards the finger, 2.5 palm-to-tip
// lengths wide, turned so that the finger points up.
std::optional<FoundHand> HandFinder::confirm(const cv::Mat& bgr, cv::Point2f palm, cv::Point2f fingertip)
{
    const cv::Point2f reach = fingertip - palm;
    const float length = std::hypot(reach.x, reach.y);
    if (!(length > 4.0f)) return std::nullopt;
    const HandCrop crop{palm + 0.3f * reach, 2.5f * length, std::atan2(reach.x, -reach.y)};
    const std::optional<SettledHand> hand = impl_->settled(bgr, crop);
    if (!hand) return std::nullopt;
    return hand->hand;
}

}  // namespace gc
