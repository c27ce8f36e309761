// The 3D step: sample textured points of the left hand, match each along its epipolar line
// inside the right hand by NCC (with a right-to-left consistency check), triangulate, fit
// the hand plane robustly, and intersect the fingertip and palm rays of both views with it.
#include "stereo/pointing.hpp"

#include "stereo/calibration_io.hpp"
#include "stereo/epipolar_ncc.hpp"
#include "stereo/extrinsics.hpp"
#include "stereo/ray_geometry.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace gc {

namespace {

constexpr int kWindowRadius = 4;       // 9x9 correlation window
constexpr double kMinScore = 0.7;      // weakest accepted NCC peak
constexpr double kMinSigma = 3.0;      // grey levels; flatter windows are sensor noise
constexpr int kMaxPoints = 128;        // correspondences attempted per frame (cost bound)
constexpr double kMinDepthMm = 250.0;  // search range along the epipolar line
constexpr double kMaxDepthMm = 5000.0;
constexpr double kConsistencyPx = 1.5;  // right-to-left match must land this close
constexpr int kMinInliers = 12;
constexpr double kMinPlaneToleranceMm = 6.0;
constexpr double kPlaneToleranceDisparityPx = 1.0;  // inlier band: this much disparity error
constexpr int kPlaneIterations = 96;
constexpr double kMinHandLengthMm = 10.0;  // palm to fingertip, below which H is noise
// Cameras turned more than this from each other: correlation windows no longer match.
constexpr double kMaxCorrelatedTurn = 15.0 * std::numbers::pi / 180.0;

Eigen::Vector3d to_eigen(const cv::Vec3d& v) { return {v[0], v[1], v[2]}; }
cv::Vec3d to_cv(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Eigen::Matrix3d to_eigen(const cv::Matx33d& m)
{
    Eigen::Matrix3d e;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) e(r, c) = m(r, c);
    return e;
}

bool has_distortion(const cv::Mat& D) { return !D.empty() && cv::countNonZero(D != 0.0) > 0; }

cv::Point2d project(const Eigen::Matrix3d& M, const Eigen::Vector3d& X)
{
    const Eigen::Vector3d p = M * X;
    return {p.x() / p.z(), p.y() / p.z()};
}

// One camera's undistortion and its per-frame working set.
struct EyeData {
    cv::Matx33d M;       // at the current zoom
    cv::Matx33d widest;  // as calibrated
    double zoom = 1.0;
    cv::Mat D;
    cv::Size size;
    bool distorted = false;
    cv::Mat map_x, map_y;                       // undistortion maps (full image), when distorted
    std::vector<cv::Point2f> raw, undistorted;  // contour + fingertip + palm
    std::vector<cv::Point> polygon;
    cv::Mat roi_bgr, grey8;
    NccView view;
    cv::Point2d fingertip, palm;

    void init(const cv::Matx33d& intrinsics, const cv::Mat& distortion, cv::Size size)
    {
        widest = M = intrinsics;
        D = distortion;
        this->size = size;
        distorted = has_distortion(distortion);
        if (distorted) cv::initUndistortRectifyMap(M, D, cv::noArray(), M, size, CV_32FC1, map_x, map_y);
    }

    // The lens's magnification for the next frames: the focal length scales, and the
    // distortion keeps its normalised coefficients (no per-zoom calibration exists).
    void set_zoom(double z)
    {
        if (z == zoom) return;
        zoom = z;
        M = zoomed_intrinsics(widest, z);
        if (distorted) cv::initUndistortRectifyMap(M, D, cv::noArray(), M, size, CV_32FC1, map_x, map_y);
    }

    // Undistorts the estimate's points and prepares the NCC view of its hand region.
    // False when the region is empty.
    bool prepare(const cv::Mat& bgr, const EyeEstimate& estimate)
    {
        raw.assign(estimate.contour.begin(), estimate.contour.end());
        raw.push_back(estimate.fingertip);
        raw.push_back(estimate.palm);
        if (distorted)
            cv::undistortPoints(raw, undistorted, M, D, cv::noArray(), M);
        else
            undistorted.assign(raw.begin(), raw.end());
        const std::size_t n = estimate.contour.size();
        fingertip = undistorted[n];
        palm = undistorted[n + 1];

        polygon.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            polygon[i] = {static_cast<int>(std::lround(undistorted[i].x)),
                          static_cast<int>(std::lround(undistorted[i].y))};
        const int pad = kWindowRadius + 1;
        cv::Rect region = cv::boundingRect(polygon);
        region = cv::Rect(region.x - pad, region.y - pad, region.width + 2 * pad, region.height + 2 * pad) &
                 cv::Rect(0, 0, bgr.cols, bgr.rows);
        if (region.width <= 2 * kWindowRadius || region.height <= 2 * kWindowRadius) return false;

        if (distorted) {
            cv::remap(bgr, roi_bgr, map_x(region), map_y(region), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
            cv::cvtColor(roi_bgr, grey8, cv::COLOR_BGR2GRAY);
        } else {
            cv::cvtColor(bgr(region), grey8, cv::COLOR_BGR2GRAY);
        }
        view.prepare(grey8, region.tl(), kWindowRadius);
        view.mask.create(region.size());
        view.mask.setTo(0);
        const cv::Point* pts = polygon.data();
        const int count = static_cast<int>(polygon.size());
        cv::fillPoly(view.mask, &pts, &count, 1, cv::Scalar(255), cv::LINE_8, 0, -region.tl());
        return true;
    }
};

}  // namespace

void direction_angles(const cv::Vec3d& d, double& azimuth_deg, double& elevation_deg)
{
    constexpr double deg = 180.0 / std::numbers::pi;
    azimuth_deg = std::atan2(d[0], d[2]) * deg;
    elevation_deg = std::atan2(-d[1], std::hypot(d[0], d[2])) * deg;
}

struct PointingEstimator::Impl {
    StereoCalibration calibration;
    EyeData left, right;
    EpipolarNcc ncc{kWindowRadius, kMinScore, kMinSigma};
    RobustPlaneFit plane_fit{kPlaneIterations, 0x9E3779B97F4A7C15ULL};
    std::vector<cv::Point> samples;
    std::vector<Eigen::Vector3d> points;
    std::vector<double> depths;
    std::vector<std::uint8_t> inliers;

    explicit Impl(const StereoCalibration& c) : calibration(c)
    {
        // cv::Mat copies share data: own the distortion so later edits by the caller
        // cannot change this estimator.
        calibration.D1 = c.D1.clone();
        calibration.D2 = c.D2.clone();
        left.init(calibration.M1, calibration.D1, c.image_size);
        right.init(calibration.M2, calibration.D2, c.image_size);
        samples.reserve(4 * kMaxPoints);
        points.reserve(kMaxPoints);
        depths.reserve(kMaxPoints);
    }

    void check_frame(const cv::Mat& bgr, const char* which) const
    {
        if (bgr.empty()) throw std::invalid_argument(std::string("pointing: empty ") + which + " frame");
        if (bgr.type() != CV_8UC3)
            throw std::invalid_argument(std::string("pointing: ") + which + " frame is not CV_8UC3 (BGR)");
        if (bgr.size() != calibration.image_size)
            throw std::invalid_argument(std::string("pointing: ") + which + " frame is " + std::to_string(bgr.cols) +
                                        "x" + std::to_string(bgr.rows) + " but the calibration '" + calibration.source +
                                        "' is for " + std::to_string(calibration.image_size.width) + "x" +
                                        std::to_string(calibration.image_size.height));
    }

    // At least a triangle, and every point finite and near the image (a diverged
    // estimate is no input for the 3D step).
    bool plausible(const EyeEstimate& e) const
    {
        const cv::Size size = calibration.image_size;
        const cv::Rect2f near(-size.width, -size.height, 3.0f * size.width, 3.0f * size.height);
        const auto ok = [&](const cv::Point2f& p) {
            return std::isfinite(p.x) && std::isfinite(p.y) && near.contains(p);
        };
        return e.contour.size() >= 3 && std::all_of(e.contour.begin(), e.contour.end(), ok) && ok(e.fingertip) &&
               ok(e.palm);
    }

    // Textured pixels of the left hand on a grid sized to give about kMaxPoints of them.
    void sample_left()
    {
        samples.clear();
        const NccView& v = left.view;
        const int area = cv::countNonZero(v.mask);
        if (area == 0) return;
        const int step = std::max(1, static_cast<int>(std::sqrt(area / (1.5 * kMaxPoints))));
        for (int y = kWindowRadius + step / 2; y < v.mask.rows - kWindowRadius; y += step)
            for (int x = kWindowRadius + step / 2; x < v.mask.cols - kWindowRadius; x += step)
                if (v.mask(y, x) && v.sigma(y, x) >= kMinSigma) samples.emplace_back(x + v.offset.x, y + v.offset.y);
        // Too many: keep an even subset (deterministic, spread over the hand).
        if (samples.size() > static_cast<std::size_t>(kMaxPoints)) {
            const double stride = static_cast<double>(samples.size()) / kMaxPoints;
            for (int i = 0; i < kMaxPoints; ++i) samples[i] = samples[static_cast<std::size_t>(i * stride)];
            samples.resize(kMaxPoints);
        }
    }

    Pointing3D estimate(const cv::Mat& left_bgr, const cv::Mat& right_bgr, const EyeEstimate& le, const EyeEstimate& re,
                        const HeadPose& head)
    {
        Pointing3D out;
        if (!le.valid() || !re.valid()) return out;
        check_frame(left_bgr, "left");
        check_frame(right_bgr, "right");
        if (!plausible(le) || !plausible(re)) return out;
        if (!std::isfinite(head.zoom) || head.zoom <= 0.0) return out;
        left.set_zoom(head.zoom);
        right.set_zoom(head.zoom);
        // The hand's plane from many correspondences holds the depth better than two
        // triangulated points where the views are close (a stereo head); where they are far
        // apart the correlation finds too little, and the key points are triangulated.
        const bool key_points = !le.landmarks.empty() && !re.landmarks.empty();
        if (key_points && views_far_apart(head)) return from_key_points(le, re, head);
        out = from_plane(left_bgr, right_bgr, le, re, head);
        if (!out.valid && key_points) return from_key_points(le, re, head);
        return out;
    }

    // Whether the two cameras look in directions so different that a correlation window in
    // one view no longer resembles the same patch in the other.
    bool views_far_apart(const HeadPose& head) const
    {
        const cv::Matx33d R = left_to_right_at(calibration, head).R;
        const double cos_angle = std::clamp((R(0, 0) + R(1, 1) + R(2, 2) - 1.0) / 2.0, -1.0, 1.0);
        return std::acos(cos_angle) > kMaxCorrelatedTurn;
    }

    // Correspondences along epipolar lines inside both hands, a robust plane through them,
    // and each view's fingertip and palm cast onto it.
    Pointing3D from_plane(const cv::Mat& left_bgr, const cv::Mat& right_bgr, const EyeEstimate& le,
                          const EyeEstimate& re, const HeadPose& head)
    {
        Pointing3D out;
        if (!left.prepare(left_bgr, le) || !right.prepare(right_bgr, re)) return out;

        const RigidTransform l2r = left_to_right_at(calibration, head);
        const Eigen::Matrix3d K1 = to_eigen(left.M), K2 = to_eigen(right.M);
        const Eigen::Matrix3d K1inv = K1.inverse(), K2inv = K2.inverse();
        const Eigen::Matrix3d R = to_eigen(l2r.R);
        const Eigen::Vector3d t = to_eigen(l2r.t);
        const Eigen::Vector3d right_origin = -R.transpose() * t;  // right centre, left frame

        sample_left();
        points.clear();
        depths.clear();
        for (const cv::Point& p : samples) {
            if (!ncc.set_template(left.view, p)) continue;
            // The left ray's points at the depth limits bound the segment in the right view.
            const Eigen::Vector3d ray_l = K1inv * Eigen::Vector3d(p.x, p.y, 1.0);
            const cv::Point2d near_r = project(K2, R * (kMinDepthMm * ray_l) + t);
            const cv::Point2d far_r = project(K2, R * (kMaxDepthMm * ray_l) + t);
            const NccMatch m = ncc.search(right.view, near_r, far_r);
            if (!m.found) continue;

            // Consistency: the right window must find its way back to p.
            if (!ncc.set_template(right.view, m.pixel)) continue;
            const Eigen::Vector3d ray_r = K2inv * Eigen::Vector3d(m.pixel.x, m.pixel.y, 1.0);
            const cv::Point2d near_l = project(K1, R.transpose() * (kMinDepthMm * ray_r - t));
            const cv::Point2d far_l = project(K1, R.transpose() * (kMaxDepthMm * ray_r - t));
            const NccMatch back = ncc.search(left.view, near_l, far_l);
            if (!back.found || cv::norm(back.position - cv::Point2d(p)) > kConsistencyPx) continue;

            const Eigen::Vector3d dir_r = R.transpose() * (K2inv * Eigen::Vector3d(m.position.x, m.position.y, 1.0));
            const auto X = triangulate_midpoint(Eigen::Vector3d::Zero(), ray_l, right_origin, dir_r);
            if (!X || X->z() < kMinDepthMm || X->z() > kMaxDepthMm) continue;
            points.push_back(*X);
            depths.push_back(X->z());
        }
        out.correspondences = static_cast<int>(points.size());
        if (points.size() < static_cast<std::size_t>(kMinInliers)) return out;

        // Inlier band: the depth error of kPlaneToleranceDisparityPx of disparity at the
        // hand's median depth (dZ = Z^2 / (f B) per pixel).
        const auto mid = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
        std::nth_element(depths.begin(), mid, depths.end());
        const double z = *mid;
        const double fb = left.M(0, 0) * std::max(1.0, t.norm());
        const double tolerance = std::max(kMinPlaneToleranceMm, kPlaneToleranceDisparityPx * z * z / fb);
        const std::optional<Plane> plane = plane_fit.fit(points, tolerance, inliers);
        if (!plane) return out;
        out.correspondences = static_cast<int>(std::count(inliers.begin(), inliers.end(), 1));
        if (out.correspondences < kMinInliers) return out;

        // Fingertip and palm: each view's 2D point cast onto the plane, averaged over views.
        const auto on_plane = [&](const cv::Point2d& pl, const cv::Point2d& pr) -> std::optional<Eigen::Vector3d> {
            const auto a = intersect(Eigen::Vector3d::Zero(), K1inv * Eigen::Vector3d(pl.x, pl.y, 1.0), *plane);
            const auto b = intersect(right_origin, R.transpose() * (K2inv * Eigen::Vector3d(pr.x, pr.y, 1.0)), *plane);
            if (a && b) return 0.5 * (*a + *b);
            if (a) return a;
            return b;
        };
        const auto F = on_plane(left.fingertip, right.fingertip);
        const auto P = on_plane(left.palm, right.palm);
        if (!F || !P) return out;
        const Eigen::Vector3d H = *F - *P;
        if (H.norm() < kMinHandLengthMm) return out;

        return finish(out, *F, *P, head);
    }

    // Both views' key points name the same fingertip and palm: each is triangulated from
    // its two rays directly, which holds for a wide baseline as for a stereo head.
    Pointing3D from_key_points(const EyeEstimate& le, const EyeEstimate& re, const HeadPose& head)
    {
        Pointing3D out;
        const RigidTransform l2r = left_to_right_at(calibration, head);
        const Eigen::Matrix3d R = to_eigen(l2r.R);
        const Eigen::Vector3d t = to_eigen(l2r.t);
        const Eigen::Vector3d right_origin = -R.transpose() * t;
        const auto ray = [](const EyeData& eye, const cv::Point2f& p) {
            std::vector<cv::Point2f> in{p}, normalised;
            cv::undistortPoints(in, normalised, eye.M, eye.D);
            return Eigen::Vector3d(normalised[0].x, normalised[0].y, 1.0);
        };
        const auto point = [&](const cv::Point2f& pl, const cv::Point2f& pr) -> std::optional<Eigen::Vector3d> {
            const auto X = triangulate_midpoint(Eigen::Vector3d::Zero(), ray(left, pl), right_origin,
                                                R.transpose() * ray(right, pr));
            if (!X || X->z() < kMinDepthMm || X->z() > kMaxDepthMm) return std::nullopt;
            return X;
        };
        const auto F = point(le.fingertip, re.fingertip);
        const auto P = point(le.palm, re.palm);
        if (!F || !P || (*F - *P).norm() < kMinHandLengthMm) return out;
        return finish(out, *F, *P, head);
    }

    // The ray from palm P to fingertip F, in the left camera's frame and the head's.
    Pointing3D finish(Pointing3D& out, const Eigen::Vector3d& F, const Eigen::Vector3d& P, const HeadPose& head) const
    {
        const Eigen::Vector3d H = F - P;
        out.fingertip_mm = to_cv(F);
        out.palm_mm = to_cv(P);
        out.direction = to_cv(H.normalized());
        direction_angles(out.direction, out.azimuth_deg, out.elevation_deg);
        const RigidTransform to_head = left_to_head_at(calibration, head);
        out.fingertip_head_mm = to_head.apply(out.fingertip_mm);
        out.palm_head_mm = to_head.apply(out.palm_mm);
        out.direction_head = to_head.R * out.direction;
        direction_angles(out.direction_head, out.azimuth_head_deg, out.elevation_head_deg);
        out.valid = true;
        return out;
    }
};

PointingEstimator::PointingEstimator(const StereoCalibration& calibration)
{
    validate_calibration(calibration);
    impl_ = std::make_unique<Impl>(calibration);
}

PointingEstimator::~PointingEstimator() = default;
PointingEstimator::PointingEstimator(PointingEstimator&&) noexcept = default;
PointingEstimator& PointingEstimator::operator=(PointingEstimator&&) noexcept = default;

Pointing3D PointingEstimator::estimate(const cv::Mat& left_bgr, const cv::Mat& right_bgr, const EyeEstimate& left,
                                       const EyeEstimate& right, const HeadPose& head)
{
    return impl_->estimate(left_bgr, right_bgr, left, right, head);
}

const StereoCalibration& PointingEstimator::calibration() const { return impl_->calibration; }

}  // namespace gc
