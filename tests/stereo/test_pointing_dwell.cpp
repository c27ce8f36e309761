// A held pointing picks the attended view's target; a wandering or brief one picks nothing;
// the target is let go after a while without pointing, and where it lands in the left view.
#include "stereo/pointing_dwell.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

constexpr double kFps = 30.0;

// A pointing from a fingertip 600 mm ahead of the head, aimed `azimuth_deg` to the right.
gc::Pointing3D pointing_at(double azimuth_deg)
{
    gc::Pointing3D p;
    p.valid = true;
    const double a = azimuth_deg * std::numbers::pi / 180.0;
    p.direction_head = {std::sin(a), 0.0, std::cos(a)};
    p.fingertip_head_mm = {0.0, 100.0, 600.0};
    return p;
}

TEST(PointingDwell, AHeldPointingPicksThePointAlongItsRayAfterTheDwell)
{
    gc::PointingDwell dwell;
    const gc::DwellParams params;  // 1 s dwell, 2 m along the ray
    double picked_at = -1.0;
    std::optional<cv::Vec3d> target;
    for (int i = 0; i < 60 && picked_at < 0.0; ++i) {
        target = dwell.update(i / kFps, pointing_at(20.0), params);
        if (target) picked_at = i / kFps;
    }
    EXPECT_NEAR(picked_at, 1.0, 1.5 / kFps);
    ASSERT_TRUE(target);
    const cv::Vec3d expected = pointing_at(20.0).fingertip_head_mm + 2000.0 * pointing_at(20.0).direction_head;
    EXPECT_LT(cv::norm(*target - expected), 1e-6);
}

// A wall 3 m ahead (z = 3000 mm in the head frame): the target is where the ray meets it; a
// ray that runs along the wall, away from it, or meets it kilometres off keeps the fixed distance.
TEST(PointingDwell, ATargetPlaneHoldsTheTargetWhereTheRayMeetsIt)
{
    gc::DwellParams params;
    params.target.plane = gc::plane_from_coefficients(0.0, 0.0, 2.0, -6000.0);  // scaled: made unit
    ASSERT_TRUE(params.target.plane);
    const cv::Vec3d on_wall = gc::pointed_target(pointing_at(20.0), params.target);
    EXPECT_NEAR(on_wall[0], 2400.0 * std::tan(20.0 * std::numbers::pi / 180.0), 1e-6);
    EXPECT_NEAR(on_wall[1], 100.0, 1e-9);
    EXPECT_NEAR(on_wall[2], 3000.0, 1e-9);

    const auto along = [](const gc::Pointing3D& p) { return p.fingertip_head_mm + 2000.0 * p.direction_head; };
    params.target.plane = gc::plane_from_coefficients(1.0, 0.0, 0.0, -5000.0);  // a side wall 5 m to the right
    EXPECT_LT(cv::norm(gc::pointed_target(pointing_at(0.0), params.target) - along(pointing_at(0.0))), 1e-9);
    EXPECT_LT(cv::norm(gc::pointed_target(pointing_at(-30.0), params.target) - along(pointing_at(-30.0))), 1e-9);
    EXPECT_LT(cv::norm(gc::pointed_target(pointing_at(0.001), params.target) - along(pointing_at(0.001))), 1e-9);
    EXPECT_NEAR(gc::pointed_target(pointing_at(30.0), params.target)[0], 5000.0, 1e-9);

    // The dwell picks the wall point.
    params.target.plane = gc::plane_from_coefficients(0.0, 0.0, 1.0, -3000.0);
    gc::PointingDwell dwell;
    std::optional<cv::Vec3d> target;
    for (int i = 0; i < 40; ++i) target = dwell.update(i / kFps, pointing_at(20.0), params);
    ASSERT_TRUE(target);
    EXPECT_LT(cv::norm(*target - on_wall), 1e-6);
}

TEST(PlaneFromCoefficients, RefusesNoNormalAndNonFiniteValues)
{
    EXPECT_FALSE(gc::plane_from_coefficients(0.0, 0.0, 0.0, -3000.0));
    EXPECT_FALSE(gc::plane_from_coefficients(0.0, std::nan(""), 1.0, 0.0));
    EXPECT_FALSE(gc::plane_from_coefficients(0.0, 0.0, 1.0, INFINITY));
    const auto plane = gc::plane_from_coefficients(0.0, -3.0, 4.0, 10.0);
    ASSERT_TRUE(plane);
    EXPECT_NEAR(plane->normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(plane->d, 2.0, 1e-12);
}

TEST(PointingDwell, AWanderingOrBriefPointingPicksNothing)
{
    gc::PointingDwell dwell;
    const gc::DwellParams params;
    for (int i = 0; i < 300; ++i) {
        // A talking hand: its direction swings 15 deg every half second.
        const double azimuth = ((i / 15) % 2 == 0) ? 0.0 : 15.0;
        EXPECT_FALSE(dwell.update(i / kFps, pointing_at(azimuth), params)) << "frame " << i;
    }
    gc::PointingDwell brief;
    gc::Pointing3D lowered;
    for (int i = 0; i < 300; ++i) {
        // Pointing for 0.8 s, then the hand drops for 0.5 s: never held long enough.
        const bool pointing = i % 39 < 24;
        EXPECT_FALSE(brief.update(i / kFps, pointing ? pointing_at(10.0) : lowered, params)) << "frame " << i;
    }
}

TEST(PointingDwell, TheTargetOutlivesShortGapsAndGoesAfterTheReleaseTime)
{
    gc::PointingDwell dwell;
    const gc::DwellParams params;  // released after 1 s without pointing
    int i = 0;
    for (; i < 45; ++i) dwell.update(i / kFps, pointing_at(-10.0), params);
    gc::Pointing3D lowered;
    const int lowered_from = i;
    for (; i < lowered_from + 20; ++i)
        EXPECT_TRUE(dwell.update(i / kFps, lowered, params)) << "a 0.67 s gap keeps the target";
    EXPECT_TRUE(dwell.update(i / kFps, pointing_at(-10.0), params));
    const int lowered_again = ++i;
    bool released = false;
    for (; i < lowered_again + 60 && !released; ++i) released = !dwell.update(i / kFps, lowered, params);
    EXPECT_TRUE(released);
    EXPECT_NEAR((i - 1 - (lowered_again - 1)) / kFps, 1.0, 1.5 / kFps);
}

TEST(PointingDwell, PointingElsewhereForTheDwellMovesTheTarget)
{
    gc::PointingDwell dwell;
    const gc::DwellParams params;
    int i = 0;
    for (; i < 40; ++i) dwell.update(i / kFps, pointing_at(-20.0), params);
    const auto first = dwell.update(i / kFps, pointing_at(-20.0), params);
    ASSERT_TRUE(first);
    std::optional<cv::Vec3d> now;
    for (int k = 0; k < 25; ++k) now = dwell.update(++i / kFps, pointing_at(25.0), params);
    ASSERT_TRUE(now);
    EXPECT_LT(cv::norm(*now - *first), 1e-9) << "0.8 s at the new place does not move it yet";
    for (int k = 0; k < 10; ++k) now = dwell.update(++i / kFps, pointing_at(25.0), params);
    ASSERT_TRUE(now);
    EXPECT_GT((*now)[0], 500.0) << "now to the right";
}

TEST(RegionInLeftView, AHeadFramePointLandsWhereTheTurnedCameraSeesIt)
{
    const gc::StereoCalibration cal = gc::default_calibration(cv::Size(640, 480));
    const double fx = cal.M1(0, 0);
    // Straight ahead of the left eye, 2 m away, at the zero pose: the principal point.
    const cv::Vec3d ahead = cal.head.left_eye_mm + cv::Vec3d(0.0, 0.0, 2000.0);
    const auto centred = gc::region_in_left_view(ahead, 500.0, cal, gc::HeadPose{});
    ASSERT_TRUE(centred);
    EXPECT_NEAR(centred->centre.x, cal.M1(0, 2), 0.5);
    EXPECT_NEAR(centred->centre.y, cal.M1(1, 2), 0.5);
    EXPECT_NEAR(centred->width_px, fx * 500.0 / 2000.0, 1.0);
    // The head panned 10 deg right: the same point is now left of centre.
    gc::HeadPose panned;
    panned.pan_deg = 10.0;
    const auto moved = gc::region_in_left_view(ahead, 500.0, cal, panned);
    ASSERT_TRUE(moved);
    EXPECT_LT(moved->centre.x, cal.M1(0, 2) - 0.8 * fx * std::tan(10.0 * std::numbers::pi / 180.0));
    // Zoomed in 2x, the panned view magnifies both the region and its offset from the centre.
    gc::HeadPose zoomed = panned;
    zoomed.zoom = 2.0;
    const auto closer = gc::region_in_left_view(ahead, 500.0, cal, zoomed);
    ASSERT_TRUE(closer);
    EXPECT_NEAR(closer->width_px, 2.0 * moved->width_px, 1e-6);
    EXPECT_NEAR(closer->centre.x - cal.M1(0, 2), 2.0 * (moved->centre.x - cal.M1(0, 2)), 1e-6);
    // Behind the camera: nowhere in the view.
    EXPECT_FALSE(gc::region_in_left_view(cal.head.left_eye_mm - cv::Vec3d(0.0, 0.0, 500.0), 500.0, cal, {}));
}

}  // namespace
