// The hand's shape model: a closed cubic B-spline through points of the segmented outline,
// taken more densely on the index finger than on the palm, with the palm centre as origin.
// Everything the per-particle measurement needs is precomputed here once, so a hypothesis
// only transforms these points (x = s R(r) u + t) and never allocates.
#pragma once

#include "contour/closed_bspline.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace gc {

struct TemplateOptions {
    int measurement_normals = 48;  // M, spread uniformly in the spline parameter
    int outline_points = 128;      // the reported polygon
    int palm_points = 96;          // outline points per perimeter away from the finger
    double finger_density = 2.5;   // how many times denser the finger is sampled
    double finger_weight = 2.0;    // measurement weight of a finger normal vs a palm normal
    double snap_range = 2.5;       // sub-pixel snapping of outline points to the skin edge
};

// Outline points within this share of the palm -> fingertip distance from the fingertip
// are on the index finger: sampled densely and weighted up.
inline constexpr double kFingerZone = 0.6;

struct HandTemplate {
    // All geometry relative to the origin (the palm centre), in pixels at scale 1.
    ClosedBSpline spline;
    std::vector<cv::Point2f> outline;    // closed polygon, dense
    std::vector<cv::Point2f> points;     // measurement points on the curve
    std::vector<cv::Point2f> normals;    // their unit outward normals
    std::vector<float> weights;          // their measurement weights, summing to 1
    std::vector<float> outline_weights;  // finger-weighting of the outline points, sum 1
    std::vector<cv::Point2f> outline_normals;
    cv::Point2f fingertip;     // index fingertip
    double palm_radius = 0.0;  // largest inscribed circle of the palm
    cv::Point2d origin_px;     // where the origin was in the capture image

    // Whether a template point (relative to the origin) lies on the index finger.
    bool on_finger(const cv::Point2f& u) const
    {
        const cv::Point2f d = u - fingertip;
        return d.dot(d) < kFingerZone * kFingerZone * fingertip.dot(fingertip);
    }

    // Builds the template from a binary hand mask (CV_8UC1, non-zero = hand). When
    // `membership` (SkinModel::membership of the same frame) is given, outline points are
    // moved to the sub-pixel skin edge, and with `bgr` too (the frame itself) on to where
    // the colour is halfway between skin and background (colour_edge_offset). `motion`
    // (optional, non-zero where the image changed recently) guides the fingertip
    // (find_hand_landmarks). Throws std::invalid_argument on a wrong type, an empty mask,
    // or a shape too small to carry a finger and a palm.
    static HandTemplate from_mask(const cv::Mat& mask, const cv::Mat1b& membership = {},
                                  const TemplateOptions& options = {}, const cv::Mat& bgr = {},
                                  const cv::Mat1b& motion = {});
};

// The palm (centre of the largest inscribed circle) and the index fingertip (the outline
// point farthest from it, ignoring points on the image border, where an arm or a cut-off
// shape ends) of a binary hand mask, found from the shape. Given `motion` (mask-sized,
// non-zero where the image changed recently), the fingertip is the farthest of the outline
// points that moved, when any did: what the hand is merged with stood still.
struct HandLandmarks {
    cv::Point2d palm;
    double palm_radius = 0.0;
    cv::Point2d fingertip;
    cv::Point2d farthest;            // the outline point farthest from the palm (the
                                     // fingertip, unless motion placed it elsewhere)
    std::vector<cv::Point> outline;  // the largest outer contour, pixel chain
};
HandLandmarks find_hand_landmarks(const cv::Mat& mask, const cv::Mat1b& motion = {});

// Proportions of a binary hand mask that tell a pointing hand from a blob merged with a
// touching object: `finger_width`, the largest inscribed-circle radius 55-95 % of the way
// from the palm centre to the fingertip, and `reach`, palm centre to fingertip, both in
// palm radii, with the fingertip of find_hand_landmarks(mask, motion). `farthest_moved`:
// the shape's farthest point is (within a palm radius) that fingertip; false when it is
// the static end of something merged with the hand. `pointing()` applies the bounds (see
// docs/tracker.md) and requires it.
struct HandProportions {
    double finger_width = 0.0;
    double reach = 0.0;
    bool farthest_moved = true;
    bool valid = false;  // false: no landmarks could be found
    bool pointing() const { return valid && farthest_moved && finger_width <= 0.33 && reach >= 1.8 && reach <= 3.0; }
};
HandProportions hand_proportions(const cv::Mat& mask, const cv::Mat1b& motion = {});

}  // namespace gc
