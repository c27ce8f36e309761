// The person around the hand: the clothed arm (forearm and upper arm as shaded tubes) and,
// for the face-pass preset, a person's head and shoulders as a billboard behind the hand.
#pragma once

#include "sim/appearance.hpp"
#include "sim/rig.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace gc::sim {

// Sub-pixel precision of all polygon drawing (fractional bits).
constexpr int kDrawShift = 4;

// Projects plane polygon points origin + a * e1 + b * e2 (head frame) into fixed-point
// pixels, minus `offset`. False when any point is within `min_depth_mm` of the camera plane.
bool project_polygon(const EyeCamera& cam, const cv::Vec3d& origin, const cv::Vec3d& e1, const cv::Vec3d& e2,
                     const std::vector<cv::Point2d>& poly, std::vector<cv::Point>& out, cv::Point offset = {},
                     double min_depth_mm = 50.0);

// A tube from `a` to `b` (head frame) with radii ra and rb: a sleeve.
struct Tube {
    cv::Vec3d a, b;
    double ra = 0.0, rb = 0.0;
};

// Draws the tube with cylinder shading and a few cloth folds; `folds` are positions along
// it in 0..1.
void draw_tube(cv::Mat& bgr, const EyeCamera& cam, const Tube& tube, const cv::Vec3f& colour,
               const std::vector<double>& folds);

// A head and shoulders facing the cameras, in its own plane (x right, y down, mm), made of
// convex layers drawn in order.
struct Billboard {
    cv::Vec3d centre_mm;
    struct Layer {
        std::vector<cv::Point2d> polygon;
        cv::Scalar colour;
        bool skin = false;  // face, ears, neck, nose
    };
    std::vector<Layer> layers;
};

// `scale` sizes the person (1: a face 200 mm high); `shaded` lights the face from one side.
Billboard build_person(const cv::Vec3d& face_centre_mm, const cv::Vec3f& skin_bgr, Rng& rng, double scale = 1.0,
                       bool shaded = false);
// With `skin_mask` (of bgr's size), also draws where the person's skin shows (255) into it
// and clears it where the person hides what is behind.
void draw_billboard(cv::Mat& bgr, const EyeCamera& cam, const Billboard& person, cv::Mat1b* skin_mask = nullptr);

}  // namespace gc::sim
