// The stereo rig's geometry at a head pose: the calibrated zero-pose extrinsics moved by the
// known vergence rotations, and the epipolar matrices derived from them.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"
#include "stereo/head_geometry.hpp"

#include <opencv2/core.hpp>

namespace gc {

// X_right = R X_left + t at `pose`, with the rig's head geometry `calibration.head` (from
// the file, or derived from T by load_calibration). The calibration is taken at the zero pose; each camera
// is assumed rigidly mounted on its eye, so the mounting error the calibration measured
// is kept and only the vergence rotations change the result (pan and tilt move both eyes
// alike). Equals (R, T) exactly at the zero pose.
RigidTransform left_to_right_at(const StereoCalibration& calibration, const HeadPose& pose);

// Left camera frame -> head frame at `pose` (the frame Pointing3D's *_head fields use).
RigidTransform left_to_head_at(const StereoCalibration& calibration, const HeadPose& pose);

// E = [t]x R, so that x_r^T E x_l = 0 for normalised image points (z = 1) of one 3D point.
cv::Matx33d essential_matrix(const RigidTransform& left_to_right);

// F = M2^-T E M1^-1, so that p_r^T F p_l = 0 for undistorted pixel points.
cv::Matx33d fundamental_matrix(const cv::Matx33d& M1, const cv::Matx33d& M2, const RigidTransform& left_to_right);

}  // namespace gc
