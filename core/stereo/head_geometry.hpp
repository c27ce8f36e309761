// The rig's kinematics: where each camera is in the head frame for a given head pose.
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

namespace gc {

// X_dst = R * X_src + t (millimetres).
struct RigidTransform {
    cv::Matx33d R = cv::Matx33d::eye();
    cv::Vec3d t{0.0, 0.0, 0.0};

    cv::Vec3d apply(const cv::Vec3d& x) const { return R * x + t; }
    RigidTransform inverse() const;
    // (a * b).apply(x) == a.apply(b.apply(x))
    friend RigidTransform operator*(const RigidTransform& a, const RigidTransform& b);
};

cv::Matx33d rotation_about_x(double deg);  // tilt: +deg looks up (y is down)
cv::Matx33d rotation_about_y(double deg);  // pan, vergence: +deg turns right

// Head frame: origin on the pan (neck) axis at the height of the baseline; at the zero pose
// x right, y down, z forward. Chain, outermost first: pan about the y axis through the
// origin; tilt about the x-parallel axis through tilt_centre_mm; each eye's vergence about
// the y-parallel axis through its eye centre; the optical centre sits nodal_offset_mm from
// the vergence centre (in the eye's own frame).
struct HeadGeometry {
    cv::Vec3d left_eye_mm{-60.0, 0.0, 0.0};
    cv::Vec3d right_eye_mm{60.0, 0.0, 0.0};
    cv::Vec3d tilt_centre_mm{0.0, 0.0, 0.0};
    cv::Vec3d nodal_offset_mm{0.0, 0.0, 0.0};

    double baseline_mm() const { return cv::norm(right_eye_mm - left_eye_mm); }
};

// The intrinsics of a camera calibrated at its widest setting when its lens magnifies by
// `zoom`: the focal lengths scale, the principal point stays (a zoom lens keeps it close).
cv::Matx33d zoomed_intrinsics(const cv::Matx33d& K, double zoom);

// Maps camera-frame points of `eye` to head-frame points at `pose`.
RigidTransform camera_to_head(const HeadGeometry& geometry, const HeadPose& pose, Eye eye);

}  // namespace gc
