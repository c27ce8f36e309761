#include "stereo/pointing_dwell.hpp"

#include "stereo/head_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc {
namespace {

// A ray that meets the target plane farther than this runs nearly along it (a grazing
// pointing at a wall): the fixed distance is the better guess.
constexpr double kFarthestPlaneTargetMm = 100000.0;

double angle_deg(const cv::Vec3d& a, const cv::Vec3d& b)
{
    const double c = a.dot(b) / std::max(cv::norm(a) * cv::norm(b), 1e-12);
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

cv::Vec3d pointed_target(const Pointing3D& pointing, const TargetPlacement& placement)
{
    const cv::Vec3d& o = pointing.fingertip_head_mm;
    const cv::Vec3d& d = pointing.direction_head;
    const Eigen::Vector3d origin(o[0], o[1], o[2]);
    if (placement.plane)
        if (const auto hit = intersect(origin, Eigen::Vector3d(d[0], d[1], d[2]), *placement.plane);
            hit && (*hit - origin).norm() <= kFarthestPlaneTargetMm)
            return {hit->x(), hit->y(), hit->z()};
    return o + placement.distance_mm * d;
}

void PointingDwell::start_dwell(double t_s, const Pointing3D& pointing)
{
    dwell_start_s_ = t_s;
    dwell_direction_ = pointing.direction_head;
    fingertip_sum_ = pointing.fingertip_head_mm;
    direction_sum_ = pointing.direction_head;
    ray_count_ = 1;
}

std::optional<cv::Vec3d> PointingDwell::update(double t_s, const Pointing3D& pointing, const DwellParams& params)
{
    if (!pointing.valid) {
        if (t_s - last_pointing_s_ > params.gap_s) dwell_start_s_.reset();  // a pointing that is not held picks nothing
        if (held_ && t_s - last_pointing_s_ >= params.release_s) held_.reset();
        return held_;
    }
    last_pointing_s_ = t_s;
    // Still aiming where the held target was picked: nothing to decide.
    if (held_ && angle_deg(pointing.direction_head, held_direction_) <= params.steady_deg) {
        dwell_start_s_.reset();
        return held_;
    }
    if (!dwell_start_s_ || angle_deg(pointing.direction_head, dwell_direction_) > params.steady_deg) {
        start_dwell(t_s, pointing);
    } else {
        fingertip_sum_ += pointing.fingertip_head_mm;
        direction_sum_ += pointing.direction_head;
        ++ray_count_;
    }
    if (t_s - *dwell_start_s_ >= params.dwell_s) {
        // The target of the dwell's mean ray: the tracker's jitter averages out, and a ray
        // grazing the target plane gives one point on it or one at the fixed distance, not a
        // mean of both.
        Pointing3D mean = pointing;
        mean.fingertip_head_mm = fingertip_sum_ * (1.0 / ray_count_);
        mean.direction_head = cv::normalize(direction_sum_);
        held_ = pointed_target(mean, params.target);
        held_direction_ = dwell_direction_;
        dwell_start_s_.reset();
        ++picks_;
    }
    return held_;
}

std::optional<ImageRegion> region_in_left_view(const cv::Vec3d& centre_mm, double size_mm,
                                               const StereoCalibration& calibration, const HeadPose& pose)
{
    const cv::Vec3d p = camera_to_head(calibration.head, pose, Eye::Left).inverse().apply(centre_mm);
    if (p[2] <= 1.0) return std::nullopt;
    const cv::Matx33d K = zoomed_intrinsics(calibration.M1, pose.zoom);
    ImageRegion r;
    r.centre = {K(0, 0) * p[0] / p[2] + K(0, 2), K(1, 1) * p[1] / p[2] + K(1, 2)};
    r.width_px = K(0, 0) * size_mm / p[2];
    return r;
}

}  // namespace gc
