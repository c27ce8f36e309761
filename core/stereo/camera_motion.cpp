#include "stereo/camera_motion.hpp"

#include "stereo/head_geometry.hpp"

#include <opencv2/calib3d.hpp>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

// Offsets of the two extra points that give rotation and scale: long enough to keep the
// angles well-conditioned, short enough to stay near the first point's depth and distortion.
constexpr double kBaselinePx = 16.0;
constexpr std::size_t kPoints = 3;  // p, p + x offset, p + y offset

using Pixels = std::array<cv::Point2d, kPoints>;
using CameraPoints = std::array<cv::Vec3d, kPoints>;

bool finite(const HeadPose& p)
{
    return std::isfinite(p.pan_deg) && std::isfinite(p.tilt_deg) && std::isfinite(p.verge_left_deg) &&
           std::isfinite(p.verge_right_deg) && std::isfinite(p.zoom) && p.zoom > 0.0;
}

bool has_distortion(const cv::Mat& d) { return !d.empty() && cv::countNonZero(d) > 0; }

// One eye's pinhole camera with its distortion; the distortion-free path avoids OpenCV's
// iterative undistortion, which is all the nominal rig needs.
struct EyeOptics {
    cv::Matx33d K;
    const cv::Mat& D;

    // Camera-frame points at depth z (along the optical axis) seen at the given pixels.
    CameraPoints back_project(const Pixels& px, double z) const
    {
        Pixels n;
        if (!has_distortion(D)) {
            for (std::size_t i = 0; i < kPoints; ++i)
                n[i] = {(px[i].x - K(0, 2)) / K(0, 0), (px[i].y - K(1, 2)) / K(1, 1)};
        } else {
            cv::Mat src(kPoints, 1, CV_64FC2, const_cast<cv::Point2d*>(px.data()));
            cv::Mat dst(kPoints, 1, CV_64FC2, n.data());
            cv::undistortPoints(src, dst, cv::Mat(K, false), D, cv::noArray(), cv::noArray(),
                                cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-12));
        }
        CameraPoints out;
        for (std::size_t i = 0; i < kPoints; ++i) out[i] = {n[i].x * z, n[i].y * z, z};
        return out;
    }

    Pixels project(const CameraPoints& points) const
    {
        Pixels out;
        if (!has_distortion(D)) {
            for (std::size_t i = 0; i < kPoints; ++i) {
                const cv::Vec3d& p = points[i];
                out[i] = {K(0, 0) * p[0] / p[2] + K(0, 2), K(1, 1) * p[1] / p[2] + K(1, 2)};
            }
            return out;
        }
        cv::Mat obj(kPoints, 1, CV_64FC3, const_cast<cv::Vec3d*>(points.data()));
        cv::Mat img(kPoints, 1, CV_64FC2, out.data());
        cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv::Mat(K, false), D, img);
        return out;
    }
};

}  // namespace

ImageMotion camera_motion(const StereoCalibration& calibration, Eye eye, const HeadPose& before, const HeadPose& after,
                          cv::Point2d image_point, double depth_mm)
{
    if (!finite(before) || !finite(after))
        throw std::invalid_argument("camera_motion: head pose angles must be finite, the zoom > 0");
    if (!std::isfinite(image_point.x) || !std::isfinite(image_point.y))
        throw std::invalid_argument("camera_motion: image point must be finite");
    if (!std::isfinite(depth_mm) || depth_mm <= 0.0)
        throw std::invalid_argument("camera_motion: depth must be finite and > 0, got " + std::to_string(depth_mm));
    if (before == after) return {};  // exactly none, not the residue of composing the poses

    const bool left = eye == Eye::Left;
    // A zoom between the poses changes the focal length the point is re-projected with.
    const cv::Matx33d& K = left ? calibration.M1 : calibration.M2;
    const cv::Mat& D = left ? calibration.D1 : calibration.D2;
    const EyeOptics optics{zoomed_intrinsics(K, before.zoom), D};
    const EyeOptics optics_after{zoomed_intrinsics(K, after.zoom), D};

    // camera at `before` -> head frame -> camera at `after`
    const RigidTransform moved =
        camera_to_head(calibration.head, after, eye).inverse() * camera_to_head(calibration.head, before, eye);

    const Pixels seen{image_point, image_point + cv::Point2d(kBaselinePx, 0.0),
                      image_point + cv::Point2d(0.0, kBaselinePx)};
    const CameraPoints points = optics.back_project(seen, depth_mm);
    CameraPoints moved_points;
    for (std::size_t i = 0; i < kPoints; ++i) {
        moved_points[i] = moved.apply(points[i]);
        if (!(moved_points[i][2] > 1e-6 * depth_mm))
            throw std::domain_error("camera_motion: the head's move puts the point behind the camera");
    }
    // Both ends re-projected, so the undistortion's residual cancels out of the difference.
    const Pixels a = optics.project(points);
    const Pixels b = optics_after.project(moved_points);

    // The local image map around the point, J (columns: where the x and y offsets go), split
    // into the similarity the hand state can express: rotation from J's rotational part, an
    // isotropic scale from its area change.
    const cv::Matx22d J_before(a[1].x - a[0].x, a[2].x - a[0].x, a[1].y - a[0].y, a[2].y - a[0].y);
    const cv::Matx22d J_after(b[1].x - b[0].x, b[2].x - b[0].x, b[1].y - b[0].y, b[2].y - b[0].y);
    const cv::Matx22d J = J_after * J_before.inv();

    ImageMotion m;
    m.dx = b[0].x - a[0].x;
    m.dy = b[0].y - a[0].y;
    // Image axes (y down): a positive angle is clockwise on screen, as HandState::rotation.
    m.drotation = std::atan2(J(1, 0) - J(0, 1), J(0, 0) + J(1, 1));
    const double area = cv::determinant(J);
    if (!(area > 0.0)) throw std::domain_error("camera_motion: the head's move folds the image around the point");
    m.scale_factor = std::sqrt(area);
    return m;
}

}  // namespace gc
