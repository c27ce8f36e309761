// C_t of the dynamics (docs/tracker.md): how a change of head pose moves a static point in
// one eye's image. The eyes rotate about centres off their optical centres (the neck, the
// tilt axis, the vergence axis), so the image motion depends a little on the point's depth.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"

#include <opencv2/core.hpp>

namespace gc {

// The image motion that moving the head from `before` to `after` causes for a static point
// seen by `eye` at `image_point` (distorted pixels, as the camera delivers them), assumed at
// `depth_mm` along that camera's optical axis (z in its frame at `before`). The point is
// back-projected, moved with the camera (gc::camera_to_head with the calibration's head
// geometry) and re-projected with the eye's intrinsics and distortion; the rotation and
// scale change come from two points a few pixels to its right and below, at the same depth
// (the similarity closest to the local image map: what the hand state can express).
// Throws std::invalid_argument on a non-finite input or a depth <= 0, and std::domain_error
// when the point ends up behind the camera (no image motion exists then).
ImageMotion camera_motion(const StereoCalibration& calibration, Eye eye, const HeadPose& before, const HeadPose& after,
                          cv::Point2d image_point, double depth_mm = 1000.0);

}  // namespace gc
