#include "stereo/head_geometry.hpp"

#include <cmath>
#include <numbers>

namespace gc {

namespace {
double rad(double deg) { return deg * std::numbers::pi / 180.0; }
}  // namespace

RigidTransform RigidTransform::inverse() const
{
    const cv::Matx33d Rt = R.t();
    return {Rt, -(Rt * t)};
}

RigidTransform operator*(const RigidTransform& a, const RigidTransform& b) { return {a.R * b.R, a.R * b.t + a.t}; }

cv::Matx33d rotation_about_x(double deg)
{
    const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
    return {1, 0, 0, 0, c, -s, 0, s, c};
}

cv::Matx33d rotation_about_y(double deg)
{
    const double c = std::cos(rad(deg)), s = std::sin(rad(deg));
    return {c, 0, s, 0, 1, 0, -s, 0, c};
}

cv::Matx33d zoomed_intrinsics(const cv::Matx33d& K, double zoom)
{
    cv::Matx33d out = K;
    out(0, 0) *= zoom;
    out(0, 1) *= zoom;
    out(1, 1) *= zoom;
    return out;
}

RigidTransform camera_to_head(const HeadGeometry& g, const HeadPose& pose, Eye eye)
{
    const bool left = eye == Eye::Left;
    const cv::Vec3d centre = left ? g.left_eye_mm : g.right_eye_mm;
    const double verge = left ? pose.verge_left_deg : pose.verge_right_deg;

    // camera -> eye (vergence about the eye centre, optical centre offset by the nodal point)
    const cv::Matx33d Rv = rotation_about_y(verge);
    const RigidTransform verge_tf{Rv, centre + Rv * g.nodal_offset_mm};
    // tilt about the axis through tilt_centre
    const cv::Matx33d Rt = rotation_about_x(pose.tilt_deg);
    const RigidTransform tilt_tf{Rt, g.tilt_centre_mm - Rt * g.tilt_centre_mm};
    // pan about the neck axis through the origin
    const RigidTransform pan_tf{rotation_about_y(pose.pan_deg), {0.0, 0.0, 0.0}};
    return pan_tf * tilt_tf * verge_tf;
}

}  // namespace gc
