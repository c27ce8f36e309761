// The simulated camera rig: pinhole intrinsics and each eye's pose from the shared head
// kinematics (stereo/head_geometry.hpp), so the renderer and the stereo code agree.
#pragma once

#include "common/types.hpp"
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "stereo/head_geometry.hpp"

#include <opencv2/core.hpp>

namespace gc::sim {

// Focal length of the default 60 degree horizontal field of view.
double default_focal_px(int width);

// fx = fy = focal, principal point at the centre of the pixel grid.
cv::Matx33d rig_intrinsics(const SceneConfig& config);
// Eyes at -/+ baseline / 2 on the x axis; tilt and vergence centres at the eyes' height.
HeadGeometry rig_geometry(const SceneConfig& config);

// One eye at one head pose.
struct EyeCamera {
    cv::Matx33d K;
    RigidTransform head_to_camera;

    cv::Vec3d to_camera(const cv::Vec3d& head_mm) const { return head_to_camera.apply(head_mm); }
    cv::Point2d project_camera(const cv::Vec3d& camera_mm) const;
    cv::Point2d project(const cv::Vec3d& head_mm) const { return project_camera(to_camera(head_mm)); }
    // Maps plane coordinates (a, b, 1) of the plane origin + a * e1 + b * e2 (head frame)
    // to homogeneous image pixels.
    cv::Matx33d plane_homography(const cv::Vec3d& origin, const cv::Vec3d& e1, const cv::Vec3d& e2) const;
    // Direction, in the head frame, of the ray through pixel (x, y).
    cv::Vec3d ray_in_head(double x, double y) const;
};

// One eye at one head pose; K is the widest setting's, narrowed by the pose's zoom.
EyeCamera eye_camera(const cv::Matx33d& K, const HeadGeometry& geometry, const HeadPose& head, Eye eye);

// X_right = R X_left + T at the zero head pose, zero distortion.
StereoCalibration rig_calibration(const SceneConfig& config);

}  // namespace gc::sim
