// The room behind the hand: a wall far from the head, textured once per scene in wall
// millimetres and warped into each view with the homography of the camera pose, so that
// panning, tilting and verging move it exactly as a real background moves.
#pragma once

#include "sim/appearance.hpp"
#include "sim/scene.hpp"

#include <opencv2/core.hpp>

namespace gc::sim {

struct Wall {
    cv::Mat3b image;
    double distance_mm = 3000.0;  // the plane z = distance_mm of the head frame
    double texel_mm = 5.0;
    cv::Point2d origin_mm;        // head-frame (x, y) of texel (0, 0)
    double skin_like_area = 0.0;  // fraction of the rest-pose view covered by skin-like material
};

// Skin-like share of the rest-pose view that each preset lays out (the thesis's figures).
double target_skin_area(Preset preset);

// `view_mm`: the wall rectangle both eyes see at the rest pose (head-frame x, y).
Wall build_wall(Preset preset, const cv::Vec3f& skin_bgr, const cv::Rect2d& view_mm, double distance_mm,
                double texel_mm, Rng& rng);

}  // namespace gc::sim
