// A hand-coloured object that the learned models take for a hand (the palm detector may even
// rate it above the hand) is part of the room: it moves only as the view does, and the
// landmark model's key points on it disagree from one check to the next. A hand rarely
// holds that still for long, and its key points settle. While the tracked hand holds still
// in the room or stays unsettled, the thesis's motion detector watches the rest of the
// frame, and a moving hand the landmark model confirms there takes over.
#include "tracker/hand_tracker_impl.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace gc {

namespace {

// Frames the tracked contour must stay with the room before another hand may take over.
constexpr int kStillFrames = 15;
// How far the contour may wander and still be still, in sides of its box (the larger).
constexpr double kStillReach = 0.1;
// Consecutive frames the landmark model disagrees with the carried key points (so checks
// it every frame) before another hand may take over.
constexpr int kUnsettledFrames = 10;
// While still or unsettled, the models look at what moves on every this-many-th frame.
constexpr int kProposeEvery = 3;
// Frames the view must hold still before the motion detector's blobs are trusted: its
// motion history (DetectionParams::history_frames).
constexpr int kQuietViewFrames = DetectionParams{}.history_frames;
// The motion detector needs this many frames before the watch's first look to give the
// maps it would give had it seen every frame: its history, plus the frame it differences
// the first one with.
constexpr int kWarmUpFrames = DetectionParams{}.history_frames + 1;
// How far around the tracked box a change is still the tracked hand's own (its motion
// since the last frame), in sides of the box (the larger).
constexpr double kOwnMotionReach = 0.25;
// The share of the tracked box a moving blob covers from which it is that hand moving.
constexpr double kSameHandCover = 0.25;

}  // namespace

void HandTracker::Impl::watch_for_moving_hand(const cv::Mat& bgr, bool view_moved)
{
    const double size = std::max(estimate.bbox.width, estimate.bbox.height);
    // The detector left unfed forgets its last frame: fed again, it starts afresh.
    const auto rest_detector = [this] {
        if (watch_fed) detector.reset();
        watch_fed = false;
    };
    if (estimate.state != TrackState::Tracking || !has_key_points || size <= 0.0) {
        still_frames = unsettled_frames = 0;
        rest_detector();
        return;
    }
    // A turn of the view moves the room by the head's motion, which only says where a point
    // at one depth goes: on such a frame the contour is anchored again and the count held.
    // The motion detector needs a still camera, so the watch looks only once the view has
    // held still for as long as the detector remembers motion.
    const cv::Point2f at(float(previous.x), float(previous.y));
    view_still_frames = view_moved ? 0 : view_still_frames + 1;
    if (view_moved) {
        still_anchor = at;
    } else if (still_frames == 0 || cv::norm(at - still_anchor) > kStillReach * size) {
        still_anchor = at;
        still_frames = 1;
    } else {
        ++still_frames;
    }
    unsettled_frames = check_interval == 1 ? unsettled_frames + 1 : 0;
    const int doubt = std::max(still_frames - kStillFrames, unsettled_frames - kUnsettledFrames);
    // Doubt grows by at most one a frame: far from a look, the motion detector is spared
    // (most tracked frames), and it starts afresh kWarmUpFrames before one could come.
    if (doubt < -kWarmUpFrames) {
        rest_detector();
        return;
    }
    watch_fed = true;
    const bool look = doubt >= 0 && doubt % kProposeEvery == 0 && view_still_frames > kQuietViewFrames;
    // The motion detector differences consecutive frames: it sees every frame from then on,
    // and segments only when the models will look and something changed away from the
    // tracked hand: change only on and around it is that hand's own, not another hand.
    const bool changed = detector.difference(bgr);
    const int reach = cvRound(kOwnMotionReach * size);
    const cv::Rect own(estimate.bbox.x - reach, estimate.bbox.y - reach, estimate.bbox.width + 2 * reach,
                       estimate.bbox.height + 2 * reach);
    if (!look || !changed || detector.changed_outside(own) < detector.min_changed_pixels()) return;
    const auto found = detector.segment_last(bgr, SkinModel::generic(), static_scene(bgr, true, {}));
    if (!found || moves_inside(*found, estimate.bbox)) return;
    const std::optional<FoundHand> moving = confirm_detection(bgr, *found);
    if (!moving || estimate.bbox.contains(cv::Point(palm_centre(moving->points)))) return;
    adopt_found(bgr, *moving);
    still_frames = unsettled_frames = 0;
}

// The moving blob is the tracked hand itself: its centre lies in the contour's box, or it
// covers much of the box (the hand moving with its arm, whose centre lies down the arm).
bool HandTracker::Impl::moves_inside(const Detection& found, const cv::Rect& box)
{
    const cv::Moments m = cv::moments(found.mask, true);
    if (m.m00 > 0.0 && box.contains(cv::Point(cvRound(m.m10 / m.m00), cvRound(m.m01 / m.m00)))) return true;
    const cv::Rect inside = box & cv::Rect(0, 0, found.mask.cols, found.mask.rows);
    return inside.area() > 0 && cv::countNonZero(found.mask(inside)) >= kSameHandCover * inside.area();
}

}  // namespace gc
