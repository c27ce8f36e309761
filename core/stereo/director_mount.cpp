#include "stereo/director_mount.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc {

namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;
}  // namespace

RigidTransform head_to_director_camera(const DirectorMount& mount, const HeadPose& pose)
{
    const RigidTransform camera_to_base{rotation_about_y(pose.pan_deg) * rotation_about_x(pose.tilt_deg), {}};
    return camera_to_base.inverse() * mount.head_to_base;
}

std::optional<DirectorPlacement> place_in_director(const DirectorMount& mount, const HeadPose& pose,
                                                   const cv::Vec3d& centre_mm, double size_mm)
{
    const cv::Vec3d p = head_to_director_camera(mount, pose).apply(centre_mm);
    if (p[2] <= 1.0 || mount.image_size.width <= 0 || mount.image_size.height <= 0) return std::nullopt;
    const cv::Matx33d K = zoomed_intrinsics(mount.K, pose.zoom);
    DirectorPlacement placed;
    placed.centre = {(K(0, 0) * p[0] / p[2] + K(0, 1) * p[1] / p[2] + K(0, 2)) / mount.image_size.width,
                     (K(1, 1) * p[1] / p[2] + K(1, 2)) / mount.image_size.height};
    placed.fill = K(0, 0) * size_mm / p[2] / mount.image_size.width;
    return placed;
}

HeadPose director_aim(const DirectorMount& mount, const cv::Vec3d& centre_mm, double size_mm, double zoom_min,
                      double zoom_max)
{
    const cv::Vec3d p = mount.head_to_base.apply(centre_mm);
    HeadPose aim;
    aim.pan_deg = std::atan2(p[0], p[2]) * kDeg;
    aim.tilt_deg = std::atan2(-p[1], std::hypot(p[0], p[2])) * kDeg;
    // The zoom at which size_mm at that distance spans the picture's width.
    const double distance = cv::norm(p);
    const double zoom = size_mm > 0.0 ? mount.image_size.width * distance / (mount.K(0, 0) * size_mm) : zoom_min;
    aim.zoom = std::clamp(zoom, zoom_min, std::max(zoom_min, zoom_max));
    return aim;
}

}  // namespace gc
