// The maps the tracker's steps read: the learnt static scene, the grey levels where the
// edges are weak, the skin mean followed inside the contour, and the filled contour.
#include "tracker/hand_tracker_impl.hpp"

#include "measure/edge_search.hpp"

#include <opencv2/imgproc.hpp>

namespace gc {

namespace {

constexpr double kAdaptRate = 0.05;

}  // namespace

// The learnt static scene when it may be consulted; nullptr while none is known.
const StaticBackground* HandTracker::Impl::known_scene() const
{
    return params.use_static_scene && !background.empty() ? &background : nullptr;
}

// Where the frame shows the static scene, over `roi` (empty: the whole frame), for a
// segmentation of this frame (`wanted`: the detector's, or the skin search after a loss);
// else, or while it is unknown, empty.
const cv::Mat1b& HandTracker::Impl::static_scene(const cv::Mat& bgr, bool wanted, cv::Rect roi)
{
    if (!wanted || !params.use_static_scene) return no_map;
    if (roi.area() == 0) roi = cv::Rect(0, 0, bgr.cols, bgr.rows);
    return background.find_static(bgr, roi);
}

// The static scene is learnt everywhere but on and around the tracked hand (its contour
// grown by the search window), so that a hand held still is not learnt into it, while the
// scene between the fingers and around the hand is.
void HandTracker::Impl::learn_background(const cv::Mat& bgr)
{
    if (!estimate.valid()) {
        background.learn(bgr);
        return;
    }
    const int grow = measurement.params().half_window;
    const cv::Rect box = cv::Rect(estimate.bbox.x - grow, estimate.bbox.y - grow, estimate.bbox.width + 2 * grow,
                                  estimate.bbox.height + 2 * grow) &
                         cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (box.area() == 0) {
        background.learn(bgr);
        return;
    }
    fill_contour(box);
    // The outline drawn 2 x grow + 1 px thick with round ends: the filled contour grown by
    // `grow` (a dilation by a disc, at a fraction of its cost).
    const cv::Point* poly = fill_points.data();
    const int count = static_cast<int>(fill_points.size());
    cv::polylines(contour_fill, &poly, &count, 1, true, 255, 2 * grow + 1);
    background.learn(bgr, box, contour_fill);
}

// The grey map over `roi`, for the normals that run from skin into skin: levels above
// kSceneGreyLevel, which is kept for the learnt scene (update_steps).
void HandTracker::Impl::update_grey(const cv::Mat& bgr, const cv::Rect& roi)
{
    if (grey.size() != bgr.size()) grey = cv::Mat1b(bgr.size(), kSceneGreyLevel);
    cv::Mat part = grey(roi);
    cv::cvtColor(bgr(roi), part, cv::COLOR_BGR2GRAY);
    cv::max(part, kSceneGreyLevel + 1, part);
}

// The grey map over `roi` with the learnt static scene blanked: in front of a face the
// step that counts is where the moving hand meets the scene behind it, and the face's own
// steps (eyes, brows, mouth), with the scene on both sides, are gone. Where no scene is
// learnt, the plain grey levels.
void HandTracker::Impl::update_steps(const cv::Mat& bgr, const cv::Rect& roi)
{
    update_grey(bgr, roi);
    const cv::Mat1b& scene = static_scene(bgr, true, roi);
    if (!scene.empty()) grey(roi).setTo(kSceneGreyLevel, scene(roi));
}

// The skin mean follows the lighting, sampled inside the tracked contour (shrunk by a few
// pixels so the boundary's mixed pixels stay out). Only the contour's box is touched.
void HandTracker::Impl::adapt_skin(const cv::Mat& bgr)
{
    const cv::Rect box = estimate.bbox & cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (box.width < 8 || box.height < 8) return;
    fill_contour(box);
    cv::erode(contour_fill, contour_fill, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
    skin->update_mean(bgr(box), contour_fill, kAdaptRate);
}

// contour_fill: the reported contour filled, over `box` (in image pixels).
void HandTracker::Impl::fill_contour(const cv::Rect& box)
{
    contour_fill.create(box.size());
    contour_fill.setTo(0);
    fill_points.resize(estimate.contour.size());
    for (std::size_t i = 0; i < fill_points.size(); ++i)
        fill_points[i] = cv::Point(cvRound(estimate.contour[i].x) - box.x, cvRound(estimate.contour[i].y) - box.y);
    const cv::Point* poly = fill_points.data();
    const int count = static_cast<int>(fill_points.size());
    cv::fillPoly(contour_fill, &poly, &count, 1, 255);
}

}  // namespace gc
