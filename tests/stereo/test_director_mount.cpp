// The director camera's geometry: the aim that frames a region, checked against hand-worked
// angles and by projecting the region back into the picture at that aim.
#include "stereo/director_mount.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

gc::DirectorMount mount_at(const cv::Vec3d& position_mm, double turned_right_deg)
{
    // X_base = R^T (X_head - position): the base turned about y, standing at `position_mm`.
    gc::DirectorMount m;
    const cv::Matx33d R = gc::rotation_about_y(turned_right_deg).t();
    m.head_to_base = {R, -(R * position_mm)};
    return m;
}

TEST(DirectorMount, AimsAtHandWorkedAngles)
{
    // 1 m to the right of the head, facing ahead; a target 1 m further right and 1 m ahead.
    const gc::DirectorMount m = mount_at({1000.0, 0.0, 0.0}, 0.0);
    gc::HeadPose aim = gc::director_aim(m, {2000.0, 0.0, 1000.0}, 500.0, 1.0, 20.0);
    EXPECT_NEAR(aim.pan_deg, 45.0, 1e-9);
    EXPECT_NEAR(aim.tilt_deg, 0.0, 1e-9);
    // 500 mm across 1920 px at sqrt(2) m with f = 1662.8 px at zoom 1.
    EXPECT_NEAR(aim.zoom, 1920.0 * std::sqrt(2.0) * 1000.0 / (1662.8 * 500.0), 1e-9);
    // Above the camera (y is down): tilt up.
    aim = gc::director_aim(m, {1000.0, -1000.0, 1000.0}, 500.0, 1.0, 20.0);
    EXPECT_NEAR(aim.pan_deg, 0.0, 1e-9);
    EXPECT_NEAR(aim.tilt_deg, 45.0, 1e-9);
    // A base turned 30 degrees right sees a target straight ahead of the head 30 degrees left.
    aim = gc::director_aim(mount_at({0.0, 0.0, 0.0}, 30.0), {0.0, 0.0, 2000.0}, 500.0, 1.0, 20.0);
    EXPECT_NEAR(aim.pan_deg, -30.0, 1e-9);
}

TEST(DirectorMount, TheAimFramesTheRegionInTheMiddle)
{
    const gc::DirectorMount m = mount_at({-700.0, -250.0, 150.0}, 20.0);
    for (const cv::Vec3d target : {cv::Vec3d(1500, -400, 2500), cv::Vec3d(-1800, 300, 1200), cv::Vec3d(200, 0, 4000)}) {
        const gc::HeadPose aim = gc::director_aim(m, target, 500.0, 1.0, 30.0);
        const auto placed = gc::place_in_director(m, aim, target, 500.0);
        ASSERT_TRUE(placed);
        // The principal point (959.5, 539.5) is half a pixel off the middle.
        EXPECT_NEAR(placed->centre.x, 0.5, 1e-3);
        EXPECT_NEAR(placed->centre.y, 0.5, 1e-3);
        EXPECT_NEAR(placed->fill, 1.0, 1e-9);
        // One degree more pan moves it left by about f * tan(1 deg) * cos(tilt) px (pan turns
        // about the base's vertical, not the tilted camera's).
        gc::HeadPose turned = aim;
        turned.pan_deg += 1.0;
        const auto moved = gc::place_in_director(m, turned, target, 500.0);
        ASSERT_TRUE(moved);
        EXPECT_LT(moved->centre.x, placed->centre.x);
        const double expected = 1662.8 * aim.zoom * std::tan(1.0 / kDeg) * std::cos(aim.tilt_deg / kDeg);
        EXPECT_NEAR((placed->centre.x - moved->centre.x) * 1920.0, expected, 0.02 * expected);
    }
}

TEST(DirectorMount, ZoomStaysInItsRangeAndPointsBehindAreNotPlaced)
{
    const gc::DirectorMount m;
    EXPECT_DOUBLE_EQ(gc::director_aim(m, {0.0, 0.0, 100000.0}, 500.0, 1.0, 12.0).zoom, 12.0);
    EXPECT_DOUBLE_EQ(gc::director_aim(m, {0.0, 0.0, 300.0}, 500.0, 1.0, 12.0).zoom, 1.0);
    // A camera without a zoom lens reports 1..1.
    EXPECT_DOUBLE_EQ(gc::director_aim(m, {0.0, 0.0, 3000.0}, 500.0, 1.0, 1.0).zoom, 1.0);
    EXPECT_FALSE(gc::place_in_director(m, gc::HeadPose{}, {0.0, 0.0, -2000.0}, 500.0));
}

}  // namespace
