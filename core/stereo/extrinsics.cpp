#include "stereo/extrinsics.hpp"

namespace gc {

RigidTransform left_to_right_at(const StereoCalibration& c, const HeadPose& pose)
{
    const HeadGeometry& g = c.head;
    const HeadPose zero{};
    const RigidTransform calibrated{c.R, c.T};
    // calibrated * (eye motion of the left camera relative to the right one since the
    // zero pose); the head-frame chains cancel pan and tilt.
    const RigidTransform left_now = camera_to_head(g, pose, Eye::Left);
    const RigidTransform right_now = camera_to_head(g, pose, Eye::Right);
    const RigidTransform left_zero = camera_to_head(g, zero, Eye::Left);
    const RigidTransform right_zero = camera_to_head(g, zero, Eye::Right);
    return calibrated * left_zero.inverse() * right_zero * right_now.inverse() * left_now;
}

RigidTransform left_to_head_at(const StereoCalibration& c, const HeadPose& pose)
{
    return camera_to_head(c.head, pose, Eye::Left);
}

cv::Matx33d essential_matrix(const RigidTransform& l2r)
{
    const cv::Vec3d& t = l2r.t;
    const cv::Matx33d tx{0.0, -t[2], t[1], t[2], 0.0, -t[0], -t[1], t[0], 0.0};
    return tx * l2r.R;
}

cv::Matx33d fundamental_matrix(const cv::Matx33d& M1, const cv::Matx33d& M2, const RigidTransform& l2r)
{
    return M2.inv().t() * essential_matrix(l2r) * M1.inv();
}

}  // namespace gc
