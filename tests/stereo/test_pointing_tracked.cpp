// The 3D step fed by the CONDENSATION trackers instead of the ground truth: a short
// scripted scene tracked end to end, the ray compared with the scene's truth.
#include "sim_pairs.hpp"

#include "sim/scene.hpp"
#include "stereo/pointing.hpp"
#include "tracker/stereo_tracker.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace {

TEST(PointingTracked, RayFromTrackedEstimates)
{
    gc::sim::SceneConfig config;
    config.preset = gc::sim::Preset::Clean;
    config.motion = gc::sim::Motion::Yaw;
    config.seed = 5;
    const gc::sim::Scene scene(config);
    const int frames = 60;
    const auto [tracking, angle, depth] = gc::test::track_scene(scene, 300, frames);
    std::printf("tracked %d / %d frames, %zu rays: angle error median %.2f deg, p90 %.2f deg; depth error "
                "median %.1f mm\n",
                tracking, frames, angle.size(), gc::test::percentile(angle, 0.5), gc::test::percentile(angle, 0.9),
                gc::test::percentile(depth, 0.5));
    ASSERT_GE(tracking, frames / 2);
    EXPECT_GE(angle.size(), static_cast<std::size_t>(tracking) * 9 / 10);
    EXPECT_LT(gc::test::percentile(angle, 0.5), 5.0);
    EXPECT_LT(gc::test::percentile(depth, 0.5), 25.0);
}

}  // namespace
