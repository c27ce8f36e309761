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
    gc::TrackerParams params;
    params.detector = gc::HandDetector::Motion;  // the contour-based path
    params.particles = 300;
    gc::StereoHandTracker trackers(params);
    gc::PointingEstimator estimator(scene.calibration());
    cv::Mat left, right;
    std::vector<double> angle, depth;
    int tracking = 0;
    const int frames = 60;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, gc::Eye::Left, {}, left);
        scene.render(f, gc::Eye::Right, {}, right);
        const gc::StereoEstimate est = trackers.process(left, right);
        if (!est.left.valid() || !est.right.valid()) continue;
        ++tracking;
        const gc::Pointing3D p = estimator.estimate(left, right, est.left, est.right);
        if (!p.valid) continue;
        const gc::sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
        angle.push_back(gc::test::angle_between_deg(p.direction_head, truth.direction));
        depth.push_back(std::abs(p.fingertip_head_mm[2] - truth.fingertip_mm[2]));
    }
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
