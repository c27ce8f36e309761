// The whole loop without GStreamer: the synthetic scene rendered from the simulated head's
// pose, the tracker with the head's camera-motion offsets, the head link steering the head
// over loopback TCP in real time. A moving hand must stay in the middle of the left view.
#include "headctl/head_link.hpp"
#include "running_head.hpp"

#include "sim/scene.hpp"
#include "tracker/pointing_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

namespace gc {
namespace {

using namespace std::chrono_literals;
using closedloop_test::eventually;
using closedloop_test::loopback_head;
using closedloop_test::RunningHead;

struct LoopFigures {
    int frames = 0;
    int first_tracked = -1;      // frame of acquisition
    int scored = 0;              // frames from one second after acquisition
    int centred = 0;             // of those, with the true palm in the central third
    int tracked = 0;             // of those, with the tracker tracking
    double max_pan_deg = 0.0;    // how far the head moved
    double error_px_sum = 0.0;   // tracked palm vs the true one, over the scored tracked frames
    double busy_s = 0.0;         // time spent processing frames
    double mean_error_px() const { return tracked ? error_px_sum / tracked : 0.0; }
    double centred_fraction() const { return scored ? double(centred) / scored : 0.0; }
    double tracked_fraction() const { return scored ? double(tracked) / scored : 0.0; }
};

bool in_central_third(cv::Point2d p, cv::Size size)
{
    return std::abs(p.x - 0.5 * size.width) < size.width / 6.0 && std::abs(p.y - 0.5 * size.height) < size.height / 6.0;
}

// Runs `seconds` of frames at the scene's frame rate, paced by the wall clock (the head
// moves in real time). Frames the machine cannot keep up with are skipped in the scene's
// script too, so the hand's motion keeps its real speed.
// With `saccades`, the hand holds still and a second client swings the head by +-20 deg
// pan every 1.5 s (up to 28 px of image motion per frame), with the link steering `mode`.
LoopFigures run_loop(SteerMode mode, double seconds, bool saccades = false)
{
    sim::SceneConfig sc;
    sc.preset = sim::Preset::Light;
    sc.motion = saccades ? sim::Motion::Static : sim::Motion::Translate;
    sc.seed = 3;
    const sim::Scene scene(sc);
    const StereoCalibration cal = scene.calibration();

    RunningHead head(loopback_head(0, 0.02));
    HeadLinkConfig lc;
    lc.uri = head.uri();
    lc.steer = mode;
    HeadLink link(lc, cal);
    EXPECT_TRUE(eventually([&] { return link.client().latest().has_value(); }, 2000ms));

    // Fast head moves commanded from outside the loop: the hand stays, the view sweeps.
    headctl::HeadClientConfig driver_config;
    driver_config.uri = head.uri();
    headctl::HeadClient driver(driver_config);
    int saccade = 0;

    TrackerParams params;
    params.particles = 500;
    params.seed = 7;
    PointingTracker tracker(params, cal);

    LoopFigures f;
    cv::Mat left, right;
    sim::EyeTruth truth;
    const cv::Size size(sc.width, sc.height);
    const auto start = std::chrono::steady_clock::now();
    const auto period = std::chrono::duration<double>(1.0 / sc.fps);
    const int last_frame = static_cast<int>(seconds * sc.fps);
    for (int i = 0; i < last_frame;) {
        std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(i * period));
        const auto busy_from = std::chrono::steady_clock::now();
        const HeadAtCapture at = link.begin_frame(link.now());
        const HeadPose pose = at.pose.value_or(HeadPose{});
        scene.render(i, Eye::Left, pose, left, &truth);
        scene.render(i, Eye::Right, pose, right);
        const FrameResult& r = tracker.process_stereo(left, right, -1, at.pose, at.left_motion, at.right_motion);
        link.end_frame(r);
        f.busy_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - busy_from).count();

        if (saccades && f.first_tracked >= 0 && i % 45 == 0) {
            headctl::HeadCommand move{headctl::CommandKind::Absolute, {}};
            move.values.set(headctl::Axis::Pan, (saccade++ % 2 == 0) ? 20.0 : -20.0);
            move.values.set(headctl::Axis::Tilt, (saccade % 3 == 0) ? 4.0 : -3.0);
            driver.submit(move);
        }
        ++f.frames;
        f.max_pan_deg = std::max(f.max_pan_deg, std::abs(pose.pan_deg));
        if (f.first_tracked < 0 && r.left.valid()) f.first_tracked = i;
        if (f.first_tracked >= 0 && i >= f.first_tracked + static_cast<int>(sc.fps)) {
            ++f.scored;
            if (truth.visible && in_central_third(truth.palm_px, size)) ++f.centred;
            if (r.left.valid()) {
                ++f.tracked;
                f.error_px_sum += std::hypot(r.left.mean.x - truth.palm_px.x, r.left.mean.y - truth.palm_px.y);
            }
        }
        // The next frame due now (skipping those the loop was too slow for).
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        i = std::max(i + 1, static_cast<int>(elapsed * sc.fps));
    }
    std::printf("steer=%s%s: %d frames in %.1f s, acquired at frame %d, scored %d: hand in the central third "
                "%.1f %%, tracked %.1f %% (palm error %.1f px), largest pan %.1f deg, %.1f ms per frame\n",
                std::string(to_string(mode)).c_str(), saccades ? " with saccades" : "", f.frames, seconds, f.first_tracked, f.scored,
                100.0 * f.centred_fraction(), 100.0 * f.tracked_fraction(), f.mean_error_px(), f.max_pan_deg,
                1000.0 * f.busy_s / std::max(f.frames, 1));
    return f;
}

TEST(ClosedLoop, FixateKeepsAMovingHandInTheMiddleOfTheView)
{
    const LoopFigures f = run_loop(SteerMode::Fixate, 10.0);
    ASSERT_GE(f.first_tracked, 0) << "the hand was never acquired";
    ASSERT_GT(f.scored, 100) << "too few frames after acquisition to judge";
    EXPECT_GE(f.centred_fraction(), 0.95);
    EXPECT_GT(f.max_pan_deg, 3.0);  // the head did follow
}

TEST(ClosedLoop, TracksAStillHandThroughFastHeadMoves)
{
    // The camera-motion offsets carry the hypotheses along with the view.
    const LoopFigures f = run_loop(SteerMode::Off, 6.0, true);
    ASSERT_GE(f.first_tracked, 0) << "the hand was never acquired";
    EXPECT_GT(f.max_pan_deg, 15.0);
    EXPECT_GE(f.tracked_fraction(), 0.95);
    EXPECT_LT(f.mean_error_px(), 10.0);
}

TEST(ClosedLoop, WithoutSteeringTheSameHandLeavesTheMiddle)
{
    // The same scene with the head at rest: the motion is wide enough that the fixate
    // figure above is the head's doing.
    const LoopFigures f = run_loop(SteerMode::Off, 10.0);
    ASSERT_GE(f.first_tracked, 0) << "the hand was never acquired";
    EXPECT_LT(f.centred_fraction(), 0.9);
    EXPECT_EQ(f.max_pan_deg, 0.0);
}

}  // namespace
}  // namespace gc
