// Head-state extrinsics, epipolar matrices, triangulation and plane fitting.
#include "stereo/calibration.hpp"
#include "stereo/extrinsics.hpp"
#include "stereo/head_geometry.hpp"
#include "stereo/ray_geometry.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace {

gc::StereoCalibration rig_with_offsets()
{
    gc::StereoCalibration c = gc::default_calibration({640, 480});
    c.M2 = cv::Matx33d(560.0, 0.0, 330.0, 0.0, 558.0, 236.0, 0.0, 0.0, 1.0);
    c.head.tilt_centre_mm = {0.0, -30.0, 20.0};
    c.head.nodal_offset_mm = {0.0, 0.0, 25.0};
    // The zero-pose extrinsics that this exact geometry implies.
    const gc::RigidTransform l2r =
        gc::camera_to_head(c.head, {}, gc::Eye::Right).inverse() * gc::camera_to_head(c.head, {}, gc::Eye::Left);
    c.R = l2r.R;
    c.T = l2r.t;
    return c;
}

double max_diff(const gc::RigidTransform& a, const gc::RigidTransform& b)
{
    return std::max(cv::norm(a.R, b.R, cv::NORM_INF), cv::norm(a.t, b.t, cv::NORM_INF));
}

const std::vector<gc::HeadPose> kPoses{
    {0, 0, 0, 0}, {10, 0, 0, 0}, {0, -15, 0, 0}, {0, 0, 5, -5}, {-20, 12, 8, -3}, {35, -20, -4, 6},
};

cv::Point2d project(const cv::Matx33d& K, const cv::Vec3d& X)
{
    const cv::Vec3d p = K * X;
    return {p[0] / p[2], p[1] / p[2]};
}

TEST(Extrinsics, ZeroPoseIsTheCalibration)
{
    gc::StereoCalibration c = gc::default_calibration({640, 480});
    // A calibration that differs from the nominal geometry (mounting error).
    c.R = gc::rotation_about_y(1.5) * gc::rotation_about_x(-0.7);
    c.T = {-118.0, 1.5, 3.0};
    const gc::RigidTransform t = gc::left_to_right_at(c, {});
    EXPECT_LT(cv::norm(t.R, c.R, cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(t.t, c.T, cv::NORM_INF), 1e-12);
}

TEST(Extrinsics, FollowsTheHeadKinematics)
{
    const gc::StereoCalibration c = rig_with_offsets();
    for (const gc::HeadPose& pose : kPoses) {
        const gc::RigidTransform expected = gc::camera_to_head(c.head, pose, gc::Eye::Right).inverse() *
                                            gc::camera_to_head(c.head, pose, gc::Eye::Left);
        EXPECT_LT(max_diff(gc::left_to_right_at(c, pose), expected), 1e-9)
            << "pan " << pose.pan_deg << " tilt " << pose.tilt_deg << " verge " << pose.verge_left_deg << "/"
            << pose.verge_right_deg;
    }
}

TEST(Extrinsics, PanAndTiltLeaveTheRigUnchangedVergenceDoesNot)
{
    const gc::StereoCalibration c = rig_with_offsets();
    const gc::RigidTransform zero = gc::left_to_right_at(c, {});
    EXPECT_LT(max_diff(gc::left_to_right_at(c, {25, -10, 0, 0}), zero), 1e-9);
    const gc::RigidTransform verged = gc::left_to_right_at(c, {0, 0, 5, -5});
    // Converging by 5 degrees per eye turns the right camera 10 degrees relative to the left.
    const double angle = std::acos(std::clamp((cv::trace(verged.R * zero.R.t()) - 1.0) / 2.0, -1.0, 1.0));
    EXPECT_NEAR(angle * 180.0 / CV_PI, 10.0, 1e-9);
}

TEST(Extrinsics, KeepsTheCalibratedMountingErrorUnderVergence)
{
    gc::StereoCalibration c = rig_with_offsets();
    const gc::RigidTransform mount{gc::rotation_about_x(0.8) * gc::rotation_about_y(-0.4), {0.5, -1.0, 0.2}};
    // The right camera sits on its eye with a small fixed error: calibration sees mount * ideal.
    const gc::RigidTransform ideal_zero = gc::left_to_right_at(c, {});
    c.R = (mount * ideal_zero).R;
    c.T = (mount * ideal_zero).t;
    const gc::HeadPose pose{5, 3, 6, -2};
    const gc::RigidTransform ideal =
        gc::camera_to_head(c.head, pose, gc::Eye::Right).inverse() * gc::camera_to_head(c.head, pose, gc::Eye::Left);
    EXPECT_LT(max_diff(gc::left_to_right_at(c, pose), mount * ideal), 1e-9);
}

TEST(Epipolar, EssentialAndFundamentalHoldOnProjectedPoints)
{
    const gc::StereoCalibration c = rig_with_offsets();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> xy(-400.0, 400.0), z(500.0, 3000.0);
    for (const gc::HeadPose& pose : kPoses) {
        const gc::RigidTransform l2r = gc::left_to_right_at(c, pose);
        const cv::Matx33d E = gc::essential_matrix(l2r);
        const cv::Matx33d F = gc::fundamental_matrix(c.M1, c.M2, l2r);
        std::vector<cv::Point2f> left_px;
        std::vector<cv::Point2d> right_px;
        for (int i = 0; i < 50; ++i) {
            const cv::Vec3d Xl(xy(rng), xy(rng), z(rng));
            const cv::Vec3d Xr = l2r.apply(Xl);
            const cv::Vec3d nl = Xl / Xl[2], nr = Xr / Xr[2];
            EXPECT_NEAR(nr.dot(E * nl), 0.0, 1e-12);
            left_px.push_back(project(c.M1, Xl));
            right_px.push_back(project(c.M2, Xr));
        }
        // The epipolar lines OpenCV derives from F pass through the true partners.
        std::vector<cv::Vec3f> lines;
        cv::computeCorrespondEpilines(left_px, 1, cv::Mat(F), lines);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const double d = lines[i][0] * right_px[i].x + lines[i][1] * right_px[i].y + lines[i][2];
            EXPECT_LT(std::abs(d), 2e-3) << "pose " << pose.pan_deg << "," << pose.verge_left_deg;
        }
    }
}

TEST(Epipolar, TheEpipolarConstraintCatchesAWrongPartner)
{
    const gc::StereoCalibration c = gc::default_calibration({640, 480});
    const gc::RigidTransform l2r = gc::left_to_right_at(c, {});
    const cv::Matx33d F = gc::fundamental_matrix(c.M1, c.M2, l2r);
    const cv::Vec3d X(50, -30, 1000);
    const cv::Point2d pl = project(c.M1, X), pr = project(c.M2, l2r.apply(X));
    const cv::Vec3d hl(pl.x, pl.y, 1.0);
    const cv::Vec3d line = F * hl;
    const double scale = std::hypot(line[0], line[1]);
    EXPECT_NEAR(cv::Vec3d(pr.x, pr.y, 1.0).dot(line) / scale, 0.0, 1e-9);
    EXPECT_NEAR(std::abs(cv::Vec3d(pr.x, pr.y + 2.0, 1.0).dot(line) / scale), 2.0, 1e-9);
}

TEST(Triangulation, ATriangulatedPointReprojectsExactly)
{
    const gc::StereoCalibration c = rig_with_offsets();
    const gc::RigidTransform l2r = gc::left_to_right_at(c, {0, 0, 4, -4});
    const cv::Matx33d K1inv = c.M1.inv(), K2inv = c.M2.inv();
    const cv::Vec3d right_origin = -(l2r.R.t() * l2r.t);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> xy(-300.0, 300.0), z(400.0, 2500.0);
    for (int i = 0; i < 100; ++i) {
        const cv::Vec3d X(xy(rng), xy(rng), z(rng));
        const cv::Point2d pl = project(c.M1, X), pr = project(c.M2, l2r.apply(X));
        const cv::Vec3d dl = K1inv * cv::Vec3d(pl.x, pl.y, 1.0);
        const cv::Vec3d dr = l2r.R.t() * (K2inv * cv::Vec3d(pr.x, pr.y, 1.0));
        const auto Y =
            gc::triangulate_midpoint({0, 0, 0}, {dl[0], dl[1], dl[2]},
                                     {right_origin[0], right_origin[1], right_origin[2]}, {dr[0], dr[1], dr[2]});
        ASSERT_TRUE(Y.has_value());
        const cv::Vec3d Yc(Y->x(), Y->y(), Y->z());
        EXPECT_LT(cv::norm(Yc - X), 1e-6);
        EXPECT_LT(cv::norm(project(c.M1, Yc) - pl), 1e-8);
        EXPECT_LT(cv::norm(project(c.M2, l2r.apply(Yc)) - pr), 1e-8);
    }
}

TEST(Triangulation, RejectsParallelRaysAndPointsBehind)
{
    const Eigen::Vector3d d(0, 0, 1);
    EXPECT_FALSE(gc::triangulate_midpoint({0, 0, 0}, d, {120, 0, 0}, d).has_value());
    // Converging rays meet in front; diverging ones only behind the cameras.
    const auto front = gc::triangulate_midpoint({0, 0, 0}, {0.1, 0, 1}, {120, 0, 0}, {-0.1, 0, 1});
    ASSERT_TRUE(front.has_value());
    EXPECT_LT((*front - Eigen::Vector3d(60, 0, 600)).norm(), 1e-9);
    EXPECT_FALSE(gc::triangulate_midpoint({0, 0, 0}, {-0.1, 0, 1}, {120, 0, 0}, {0.1, 0, 1}).has_value());
}

TEST(Plane, RayPlaneIntersection)
{
    gc::Plane plane;
    plane.normal = Eigen::Vector3d(0, 0, 1);
    plane.d = -1000.0;
    const auto p = gc::intersect({0, 0, 0}, {0.1, -0.2, 1.0}, plane);
    ASSERT_TRUE(p.has_value());
    EXPECT_LT((*p - Eigen::Vector3d(100, -200, 1000)).norm(), 1e-9);
    EXPECT_FALSE(gc::intersect({0, 0, 0}, {1, 0, 0}, plane).has_value());     // parallel
    EXPECT_FALSE(gc::intersect({0, 0, 2000}, {0, 0, 1}, plane).has_value());  // behind
}

TEST(Plane, RobustFitIgnoresOutliers)
{
    const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.2, -1.0).normalized();
    const Eigen::Vector3d centre(40, -20, 1100);
    const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> in_plane(-60.0, 60.0), off(-150.0, 150.0);
    std::normal_distribution<double> noise(0.0, 1.5);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 120; ++i)
        points.push_back(centre + in_plane(rng) * u + in_plane(rng) * v + noise(rng) * normal);
    for (int i = 0; i < 50; ++i) points.push_back(centre + in_plane(rng) * u + in_plane(rng) * v + off(rng) * normal);

    std::vector<std::uint8_t> inliers;
    const auto plane = gc::RobustPlaneFit(96, 1).fit(points, 6.0, inliers);
    ASSERT_TRUE(plane.has_value());
    EXPECT_GT(std::abs(plane->normal.dot(normal)), std::cos(1.0 * CV_PI / 180.0));
    EXPECT_LT(plane->distance(centre), 1.0);
    int kept = 0;
    for (int i = 0; i < 120; ++i) kept += inliers[i];
    EXPECT_GT(kept, 110);

    // A plain least-squares fit over everything is pulled away: the robust step matters.
    const std::vector<std::uint8_t> all(points.size(), 1);
    const auto naive = gc::fit_plane(points, all);
    ASSERT_TRUE(naive.has_value());
    EXPECT_LT(std::abs(naive->normal.dot(normal)), std::abs(plane->normal.dot(normal)));
}

TEST(Plane, CollinearPointsHaveNoPlane)
{
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 10; ++i) points.emplace_back(i, 2.0 * i, 1000.0 + i);
    const std::vector<std::uint8_t> all(points.size(), 1);
    EXPECT_FALSE(gc::fit_plane(points, all).has_value());
    std::vector<std::uint8_t> inliers;
    EXPECT_FALSE(gc::RobustPlaneFit(32, 1).fit(points, 1.0, inliers).has_value());
}

}  // namespace
