// The fixate steering law against the simulated head (fake clock, frame-rate control loop).
#include "headctl/steering/fixate_controller.hpp"
#include "headctl/sim/head_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <deque>

namespace gc::headctl {
namespace {

constexpr double kFrame = 1.0 / 30.0;

// A target fixed in the world at (pan, tilt); the camera sees it relative to the head's
// pose one frame late (capture + processing), and the head obeys after its own latency.
struct Loop {
    explicit Loop(FixateConfig config = {}, double latency_s = 0.02) : controller(with_limits(config))
    {
        HeadModelConfig m;
        m.latency_s = latency_s;
        head = std::make_unique<HeadModel>(m);
    }
    static FixateConfig with_limits(FixateConfig c)
    {
        c.limits = default_simulated_limits();
        return c;
    }

    // Runs n frames; returns the pan/tilt poses seen at each.
    std::vector<HeadPose> run(int frames, double target_pan, double target_tilt, bool visible = true)
    {
        std::vector<HeadPose> poses;
        for (int i = 0; i < frames; ++i) {
            const HeadPose now = head->state(t).pose;
            FixateObservation seen;
            seen.valid = visible;
            seen.offset_pan_deg = target_pan - delayed.pan_deg;
            seen.offset_tilt_deg = target_tilt - delayed.tilt_deg;
            delayed = now;
            const auto cmd = controller.update(seen, now, kFrame);
            if (cmd) {
                commands.push_back(*cmd);
                if (cmd->kind == CommandKind::Velocity) head->move_velocity(cmd->values, t);
                if (cmd->kind == CommandKind::Absolute) head->move_absolute(cmd->values, t);
                if (cmd->kind == CommandKind::Home) head->home(t);
                if (cmd->kind == CommandKind::RecallPreset) head->recall_preset(cmd->preset, t);
            }
            poses.push_back(now);
            t += kFrame;
        }
        return poses;
    }

    FixateController controller;
    std::unique_ptr<HeadModel> head;
    HeadPose delayed;
    double t = 0.0;
    std::vector<HeadCommand> commands;
};

TEST(FixateController, StepResponseSettlesWithoutOvershootOrOscillation)
{
    for (double step : {5.0, 20.0, -40.0}) {
        Loop loop;
        const auto poses = loop.run(150, step, step / 4.0);  // 5 s
        double overshoot_pan = 0.0;
        double overshoot_tilt = 0.0;
        for (const HeadPose& p : poses) {
            overshoot_pan = std::max(overshoot_pan, (p.pan_deg - step) * (step > 0 ? 1 : -1));
            overshoot_tilt = std::max(overshoot_tilt, (p.tilt_deg - step / 4.0) * (step > 0 ? 1 : -1));
        }
        std::printf("step %+.0f deg: overshoot pan %.3f tilt %.3f deg, error after 2 s %.3f deg, final %.3f deg\n",
                    step, overshoot_pan, overshoot_tilt, std::abs(poses[60].pan_deg - step),
                    std::abs(poses.back().pan_deg - step));
        EXPECT_LE(overshoot_pan, 2.0) << step;
        EXPECT_LE(overshoot_tilt, 2.0) << step;
        EXPECT_NEAR(poses.back().pan_deg, step, 2.0) << step;  // within the release band
        // At rest: the last 2 s are still, every command zero.
        const double settled = poses[90].pan_deg;
        for (std::size_t i = 90; i < poses.size(); ++i) EXPECT_NEAR(poses[i].pan_deg, settled, 1e-6) << step;
        for (std::size_t i = 90; i < loop.commands.size(); ++i) {
            EXPECT_EQ(loop.commands[i].values.get(Axis::Pan), 0.0);
            EXPECT_EQ(loop.commands[i].values.get(Axis::Tilt), 0.0);
        }
        // It got there reasonably fast: within 1 deg of the target after 2 s.
        EXPECT_NEAR(poses[60].pan_deg, step, 1.0) << step;
    }
}

TEST(FixateController, CommandsAreRateLimited)
{
    FixateConfig config;
    config.max_acceleration_dps2 = 100.0;
    Loop loop(config);
    loop.run(60, 60.0, 0.0);
    double previous = 0.0;
    for (const HeadCommand& c : loop.commands) {
        const double v = c.values.get(Axis::Pan);
        EXPECT_LE(std::abs(v - previous), 100.0 * kFrame + 1e-9);
        EXPECT_LE(std::abs(v), config.max_velocity_dps + 1e-9);
        previous = v;
    }
}

TEST(FixateController, StopsInsideTheSoftLimits)
{
    Loop loop;
    const auto poses = loop.run(300, 200.0, 80.0);  // far beyond pan 170, tilt 45
    // It aims 1 deg (the margin) inside; the head's own lag may carry it a little further.
    for (const HeadPose& p : poses) {
        EXPECT_LE(p.pan_deg, 169.1);
        EXPECT_LE(p.tilt_deg, 44.1);
    }
    EXPECT_NEAR(poses.back().pan_deg, 169.0, 0.5);
}

TEST(FixateController, HoldsThenHomesWhenTheHandIsLost)
{
    FixateConfig config;
    config.hold_s = 1.0;
    Loop loop(config);
    loop.run(90, 30.0, 0.0);
    const double held = loop.head->state(loop.t).pose.pan_deg;
    loop.commands.clear();
    const auto lost = loop.run(20, 30.0, 0.0, false);  // 0.67 s: holding
    EXPECT_NEAR(lost.back().pan_deg, held, 0.5);
    for (const HeadCommand& c : loop.commands) EXPECT_EQ(c.kind, CommandKind::Velocity);
    loop.commands.clear();
    const auto later = loop.run(90, 30.0, 0.0, false);
    // Zero velocities until hold_s has passed, then one Home, then nothing.
    ASSERT_FALSE(loop.commands.empty());
    EXPECT_EQ(loop.commands.back().kind, CommandKind::Home);
    EXPECT_LE(loop.commands.size(), 12u);
    for (std::size_t i = 0; i + 1 < loop.commands.size(); ++i) {
        EXPECT_EQ(loop.commands[i].kind, CommandKind::Velocity);
        EXPECT_EQ(loop.commands[i].values.get(Axis::Pan), 0.0);
    }
    EXPECT_NEAR(later.back().pan_deg, 0.0, 1e-6);
}

TEST(FixateController, ReturnsToTheHomePresetWhenOneIsSet)
{
    FixateConfig config;
    config.hold_s = 0.5;
    config.home_preset = 7;
    Loop loop(config);
    AxisValues watch;
    watch.set(Axis::Pan, -25.0);
    watch.set(Axis::Tilt, 5.0);
    loop.head->move_absolute(watch, 0.0);
    loop.head->save_preset(7, 2.0);
    loop.t = 2.0;
    loop.run(90, 10.0, 0.0);  // follows the hand away from the preset
    loop.commands.clear();
    const auto later = loop.run(90, 10.0, 0.0, false);
    ASSERT_FALSE(loop.commands.empty());
    EXPECT_EQ(loop.commands.back(), preset_command(CommandKind::RecallPreset, 7));
    EXPECT_NEAR(later.back().pan_deg, -25.0, 1e-6);
    EXPECT_NEAR(later.back().tilt_deg, 5.0, 1e-6);
}

TEST(FixateController, ZoomsOutWhileTheHandIsLostAndStopsWhenItIsFoundAgain)
{
    FixateConfig config;
    config.widen_after_s = 0.5;
    config.widen_rate = 3.0;
    config.hold_s = 10.0;
    Loop loop(config);
    AxisValues zoomed;
    zoomed.set(Axis::Zoom, 6.0);
    loop.head->move_absolute(zoomed, 0.0);
    loop.t = 3.0;
    loop.run(30, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(loop.head->state(loop.t).pose.zoom, 6.0);  // tracking: the lens is left alone
    const auto lost = loop.run(15, 0.0, 0.0, false);            // 0.5 s: holding
    EXPECT_DOUBLE_EQ(lost.back().zoom, 6.0);
    const auto widening = loop.run(30, 0.0, 0.0, false);  // 1 s more: about 3 wider
    EXPECT_LT(widening.back().zoom, 4.0);
    EXPECT_GT(widening.back().zoom, 2.0);
    loop.run(1, 0.0, 0.0);  // found again
    const double found = loop.head->state(loop.t).pose.zoom;
    loop.run(30, 0.0, 0.0);
    EXPECT_NEAR(loop.head->state(loop.t).pose.zoom, found, 0.3);  // stopped (after its braking)
    EXPECT_GT(loop.head->state(loop.t).pose.zoom, 1.5);
}

TEST(FixateController, FeedForwardFollowsAMovingTarget)
{
    FixateConfig with;
    FixateConfig without;
    without.feed_forward = 0.0;
    auto lag = [](FixateConfig config) {
        Loop loop(config);
        double target = 0.0;
        double worst = 0.0;
        for (int i = 0; i < 120; ++i) {
            const HeadPose now = loop.head->state(loop.t).pose;
            FixateObservation seen;
            seen.valid = true;
            seen.offset_pan_deg = target - now.pan_deg;
            seen.rate_pan_dps = 15.0;
            const auto cmd = loop.controller.update(seen, now, kFrame);
            loop.head->move_velocity(cmd->values, loop.t);
            if (i > 60) worst = std::max(worst, std::abs(target - now.pan_deg));
            loop.t += kFrame;
            target += 15.0 * kFrame;
        }
        return worst;
    };
    EXPECT_LT(lag(with), 1.0);
    EXPECT_GT(lag(without), lag(with));
}

TEST(FixateController, ImageOffsetsBecomeAnglesInTheHeadsSense)
{
    const FixateObservation o = offset_from_image(100.0, -100.0, 100.0, 100.0);
    EXPECT_NEAR(o.offset_pan_deg, 45.0, 1e-9);   // right of centre: pan right
    EXPECT_NEAR(o.offset_tilt_deg, 45.0, 1e-9);  // above centre: tilt up
    EXPECT_THROW(offset_from_image(1.0, 1.0, 0.0, 100.0), std::invalid_argument);
    EXPECT_THROW(offset_from_image(std::nan(""), 1.0, 100.0, 100.0), std::invalid_argument);
}

TEST(FixateController, RejectsBadConfigurationAndInput)
{
    FixateConfig config;
    config.release_band_deg = 0.5;  // below the dead band
    EXPECT_THROW(FixateController{config}, std::invalid_argument);
    config = {};
    config.gain_per_s = 0.0;
    EXPECT_THROW(FixateController{config}, std::invalid_argument);
    FixateController c{FixateConfig{}};
    FixateObservation seen;
    seen.valid = true;
    EXPECT_THROW(c.update(seen, HeadPose{}, 0.0), std::invalid_argument);
    seen.offset_pan_deg = std::numeric_limits<double>::infinity();
    EXPECT_THROW(c.update(seen, HeadPose{}, kFrame), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl
