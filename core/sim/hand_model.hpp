// The planar hand in a rigid pointing gesture: palm, short wrist, extended index finger,
// thumb along it, the other three fingers curled against the palm. Geometry in the hand's
// own plane (millimetres): u runs from the palm centroid (the origin) to the index
// fingertip, v to the thumb's side. The outline is a union of convex parts; the skin
// texture is an image over the same plane.
#pragma once

#include "sim/appearance.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace gc::sim {

struct HandModel {
    std::vector<std::vector<cv::Point2d>> parts;  // convex polygons, model millimetres
    double finger_length_mm = 0.0;  // palm centroid to fingertip; the tip is (length, 0)
    cv::Point2d palm_axis{-1.0, 0.0};  // unit, from the palm centroid towards the wrist
    double wrist_mm = 0.0;             // where the skin of the wrist ends along palm_axis

    cv::Mat3b texture;                 // skin albedo under full light
    double texel_mm = 0.0;
    cv::Point2d texture_origin;        // model (u, v) of texel (0, 0); rows run towards -v

    // Texel (i, j, 1) -> model (u, v, 1).
    cv::Matx33d texel_to_model() const;
};

// `mirrored` gives the other hand (thumb on the -v side, seen from the palm).
HandModel build_hand_model(const cv::Vec3f& skin_bgr, bool mirrored, Rng& rng);

}  // namespace gc::sim
