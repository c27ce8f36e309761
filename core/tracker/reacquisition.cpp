// A known hand found again after a loss: the template is placed on a detected blob, or on
// the skin blobs of the frame, and tracking resumes if it measures as well as it did.
#include "tracker/hand_tracker_impl.hpp"

#include "measure/contour_fit.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

namespace {

const FitParams kRefit{8, 8.0, 0.5, 2.0, 0.5};

}  // namespace

// Places the known template on a detected blob (palm to palm, finger direction to finger
// direction), refines, and resumes tracking if it measures as well as tracking did
// (lost_ratio x P_init).
bool HandTracker::Impl::refit_known_shape(const Detection& found, const cv::Mat1b& memb, const cv::Mat& bgr)
{
    HandLandmarks lm;
    try {
        lm = find_hand_landmarks(found.mask, found.motion);
    } catch (const std::invalid_argument&) {
        return false;
    }
    const double reach = std::hypot(shape->fingertip.x, shape->fingertip.y);
    const double found_reach = std::hypot(lm.fingertip.x - lm.palm.x, lm.fingertip.y - lm.palm.y);
    if (reach <= 0.0 || found_reach <= 0.0) return false;
    const HandState guess{lm.palm.x, lm.palm.y,
                          std::atan2(lm.fingertip.y - lm.palm.y, lm.fingertip.x - lm.palm.x) -
                              std::atan2(shape->fingertip.y, shape->fingertip.x),
                          std::clamp(found_reach / reach, tracking::kMinScale, tracking::kMaxScale), previous.squash};
    const FitResult fit = refine_fit(memb, *shape, guess, kRefit);
    if (!fit.converged) return false;
    update_grey(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows));
    const double like = measurement.normal_likelihood(measurement.misfit(memb, grey, *shape, fit.state));
    if (like < params.lost_ratio * p_init) return false;
    skin = found.skin;
    start_tracking(fit.state);
    awaiting_p_init = false;
    report(fit.state);
    return true;
}

// Re-initialisation guided by the skin map: the largest skin blobs of a plausible size are
// tried as palm positions at the last rotation and scale; the best fit is taken if it
// measures as well as tracking did (lost_ratio x P_init).
bool HandTracker::Impl::reacquire_by_skin(const cv::Mat& bgr)
{
    cv::Mat1b seg;
    skin->segment(bgr, seg);
    // Skin of the static scene (a face the hand was lost in front of) is left out, as the
    // detector does: the hand's blob is then the hand's alone.
    const cv::Mat1b& scene = static_scene(bgr, true, {});
    if (!scene.empty()) seg.setTo(0, scene);
    cv::morphologyEx(seg, seg, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int count = cv::connectedComponentsWithStats(seg, labels, stats, centroids, 8, CV_32S);
    const double template_area = std::max(1.0, cv::contourArea(shape->outline));
    const double scale = estimate.mean.scale;
    skin->membership(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), membership);
    membership_roi = cv::Rect(0, 0, bgr.cols, bgr.rows);
    update_grey(bgr, membership_roi);
    double best_like = 0.0;
    HandState best_state;
    for (int i = 1; i < count; ++i) {
        const double area = stats.at<int>(i, cv::CC_STAT_AREA);
        const double ratio = area / (template_area * scale * scale * estimate.mean.squash);
        if (ratio < 0.4 || ratio > 3.0) continue;
        // The palm is the blob's thickest point.
        const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                           stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
        cv::Mat1b blob = labels(box) == i;
        cv::copyMakeBorder(blob, blob, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
        cv::Mat1f dist;
        cv::distanceTransform(blob, dist, cv::DIST_L2, cv::DIST_MASK_5);
        cv::Point at;
        cv::minMaxLoc(dist, nullptr, nullptr, nullptr, &at);
        const HandState guess{double(box.x + at.x - 1), double(box.y + at.y - 1), estimate.mean.rotation, scale,
                              estimate.mean.squash};
        const FitResult fit = refine_fit(membership, *shape, guess, kRefit);
        if (!fit.converged) continue;
        const double like = measurement.normal_likelihood(measurement.misfit(membership, grey, *shape, fit.state));
        if (like > best_like) {
            best_like = like;
            best_state = fit.state;
        }
    }
    if (best_like < params.lost_ratio * p_init || best_like <= 0.0) return false;
    start_tracking(best_state);
    awaiting_p_init = false;  // the hand is known: keep the reference likelihood
    report(best_state);
    return true;
}

}  // namespace gc
