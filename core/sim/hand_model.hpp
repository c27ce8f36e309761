// The planar hand in one rigid gesture; pointing: palm, short wrist, extended index finger,
// thumb along it, the other three fingers curled against the palm (open and fist: see
// hand_gestures.hpp). Geometry in the hand's own plane (millimetres): u runs from the palm
// centroid (the origin) to the pointing index fingertip, v to the thumb's side. The outline is a union of convex parts; the skin
// texture is an image over the same plane.
#pragma once

#include "common/types.hpp"
#include "sim/appearance.hpp"

#include <opencv2/core.hpp>

#include <array>
#include <vector>

namespace gc::sim {

// The hand's proportions in model millimetres (before the seeded +/-5 % size): the defaults
// are the one hand of the presets without variety.
struct HandShape {
    double palm_half_length = 45.0;      // along u
    double palm_half_width = 40.0;       // along v
    double palm_exponent = 4.0;          // of the superellipse outline: 2 an ellipse, more squarer
    cv::Point2d index_base{32.0, 24.0};  // centre of the index finger's root
    double index_base_radius = 9.5;
    cv::Point2d index_tip{108.0, 24.0};  // centre of its end cap
    double index_tip_radius = 8.2;
    cv::Point2d thumb_base{-2.0, 36.0};
    double thumb_base_radius = 12.5;
    cv::Point2d thumb_tip{30.0, 44.0};
    double thumb_tip_radius = 10.0;
    // Middle, ring and little finger curled against the palm: ellipses.
    std::array<cv::Point2d, 3> curled_centre{{{46.0, 5.0}, {43.0, -15.0}, {38.0, -32.0}}};
    std::array<double, 3> curled_length{15.5, 14.5, 12.0};
    std::array<double, 3> curled_width{10.5, 10.0, 8.5};
    std::array<double, 3> curled_angle_deg{-8.0, 0.0, 10.0};
    double wrist_length = 80.0;      // from the palm centre to where the skin of the wrist ends
    double wrist_half_width = 27.0;  // at that end; 4 mm wider where it meets the palm
};

// The skin of a hand of the wide variety: the palm's tone, the back's tone (seen towards the
// silhouette, where the hand's side turns to the camera), and how strong the shading is.
struct HandSkin {
    cv::Vec3f palm;
    cv::Vec3f back;
    double rim_mm = 4.0;     // width of the blend from the palm's tone to the back's
    double gradient = 0.07;  // brightness change across the hand (per 80 mm)
    double blotches = 0.03;  // amplitude of the brightness blotches
};

struct HandModel {
    Gesture gesture = Gesture::Pointing;
    std::vector<std::vector<cv::Point2d>> parts;  // convex polygons, model millimetres
    // Palm centroid to the fingertip, which is (length, 0); for a hand that does not point,
    // to the hand's farthest reach along u.
    double finger_length_mm = 0.0;
    cv::Point2d palm_axis{-1.0, 0.0};             // unit, from the palm centroid towards the wrist
    double wrist_mm = 0.0;                        // where the skin of the wrist ends along palm_axis

    cv::Mat3b texture;  // skin albedo under full light
    double texel_mm = 0.0;
    cv::Point2d texture_origin;  // model (u, v) of texel (0, 0); rows run towards -v

    // Texel (i, j, 1) -> model (u, v, 1).
    cv::Matx33d texel_to_model() const;
};

// `mirrored` gives the other hand (thumb on the -v side, seen from the palm). Without `skin`,
// one tone `skin_bgr` with the presets' shading; with it, that skin (skin_bgr unused). The
// same `rng` state gives the same hand (size, skin) in every gesture.
HandModel build_hand_model(const cv::Vec3f& skin_bgr, bool mirrored, Rng& rng, const HandShape& shape = {},
                           const HandSkin* skin = nullptr, Gesture gesture = Gesture::Pointing);

}  // namespace gc::sim
