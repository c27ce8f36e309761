#include "sim/rig.hpp"

#include <cmath>
#include <numbers>

namespace gc::sim {

double default_focal_px(int width)
{
    constexpr double kHalfFovRad = 30.0 * std::numbers::pi / 180.0;
    return 0.5 * width / std::tan(kHalfFovRad);
}

cv::Matx33d rig_intrinsics(const SceneConfig& c)
{
    const double f = c.focal_px > 0.0 ? c.focal_px : default_focal_px(c.width);
    return {f, 0.0, 0.5 * (c.width - 1), 0.0, f, 0.5 * (c.height - 1), 0.0, 0.0, 1.0};
}

HeadGeometry rig_geometry(const SceneConfig& c)
{
    HeadGeometry g;
    g.left_eye_mm = {-0.5 * c.baseline_mm, 0.0, 0.0};
    g.right_eye_mm = {0.5 * c.baseline_mm, 0.0, 0.0};
    g.tilt_centre_mm = {0.0, 0.0, 0.0};
    g.nodal_offset_mm = {0.0, 0.0, 0.0};
    return g;
}

cv::Point2d EyeCamera::project_camera(const cv::Vec3d& p) const
{
    return {K(0, 0) * p[0] / p[2] + K(0, 2), K(1, 1) * p[1] / p[2] + K(1, 2)};
}

cv::Matx33d EyeCamera::plane_homography(const cv::Vec3d& origin, const cv::Vec3d& e1, const cv::Vec3d& e2) const
{
    const cv::Matx33d& R = head_to_camera.R;
    const cv::Vec3d c1 = R * e1;
    const cv::Vec3d c2 = R * e2;
    const cv::Vec3d c3 = head_to_camera.apply(origin);
    const cv::Matx33d M(c1[0], c2[0], c3[0], c1[1], c2[1], c3[1], c1[2], c2[2], c3[2]);
    return K * M;
}

cv::Vec3d EyeCamera::ray_in_head(double x, double y) const
{
    const cv::Vec3d d((x - K(0, 2)) / K(0, 0), (y - K(1, 2)) / K(1, 1), 1.0);
    return head_to_camera.R.t() * d;
}

EyeCamera eye_camera(const cv::Matx33d& K, const HeadGeometry& geometry, const HeadPose& head, Eye eye)
{
    return {zoomed_intrinsics(K, head.zoom), camera_to_head(geometry, head, eye).inverse()};
}

StereoCalibration rig_calibration(const SceneConfig& c)
{
    StereoCalibration cal;
    cal.image_size = {c.width, c.height};
    cal.M1 = rig_intrinsics(c);
    cal.M2 = cal.M1;
    cal.D1 = cv::Mat::zeros(1, 5, CV_64F);
    cal.D2 = cv::Mat::zeros(1, 5, CV_64F);
    const HeadGeometry g = rig_geometry(c);
    const HeadPose zero;
    const RigidTransform left_to_right =
        camera_to_head(g, zero, Eye::Right).inverse() * camera_to_head(g, zero, Eye::Left);
    cal.R = left_to_right.R;
    cal.T = left_to_right.t;
    cal.has_head_geometry = true;
    cal.head = g;
    cal.source = "synthetic scene";
    return cal;
}

}  // namespace gc::sim
