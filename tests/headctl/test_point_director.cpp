// steer=point's plan on a fake clock and a fake head that moves to where it is sent: a held
// pointing turns the head to its target, the head looks there for the look time and comes
// back to the pose it left; no pick moves nothing; a new pick while looking re-targets; the
// same pointing, still held, is not looked at twice.
#include "headctl/steering/point_director.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace {

using gc::HeadPose;
using gc::headctl::PointAim;
using gc::headctl::PointDirector;
using gc::headctl::PointDirectorConfig;
using gc::headctl::PointPhase;
using gc::headctl::PointStep;

constexpr double kFps = 30.0;

// Moves pan and tilt towards the last absolute goal at 60 deg/s; a Follow step leaves it
// where it is (the fixate law is not simulated here).
struct FakeHead {
    int frame = 0;  // the fake clock: frames at 30 Hz
    HeadPose pose;
    std::optional<std::pair<double, double>> goal;
    void obey(const PointStep& step)
    {
        if (step.kind == PointStep::Kind::Aim) goal = std::pair{step.aim.pan_deg, step.aim.tilt_deg};
        if (step.kind == PointStep::Kind::Return) goal = std::pair{step.pose.pan_deg, step.pose.tilt_deg};
    }
    void advance(double dt)
    {
        if (!goal) return;
        const double max_step = 60.0 * dt;
        pose.pan_deg += std::clamp(goal->first - pose.pan_deg, -max_step, max_step);
        pose.tilt_deg += std::clamp(goal->second - pose.tilt_deg, -max_step, max_step);
    }
};

PointAim aim_at(double pan, double tilt) { return PointAim{cv::Vec3d(0, 0, 2000), pan, tilt}; }

struct Trace {
    std::vector<PointStep> steps;
    std::vector<HeadPose> poses;
    std::vector<PointPhase> phases;
};

// Frames at 30 Hz for `seconds` after those of the previous runs on the same head;
// `pick(i)` gives the pick of the run's i-th frame.
template <class Pick>
Trace run(PointDirector& director, FakeHead& head, double seconds, Pick pick, bool pointing = true)
{
    Trace r;
    const int n = static_cast<int>(seconds * kFps);
    for (int i = 0; i < n; ++i, ++head.frame) {
        const PointStep step = director.update(head.frame / kFps, pick(i), pointing, true, head.pose);
        head.obey(step);
        head.advance(1.0 / kFps);
        r.steps.push_back(step);
        r.poses.push_back(head.pose);
        r.phases.push_back(director.phase());
    }
    return r;
}

int count(const Trace& r, PointStep::Kind kind)
{
    return static_cast<int>(std::count_if(r.steps.begin(), r.steps.end(), [&](const PointStep& s) { return s.kind == kind; }));
}

TEST(PointDirector, AHeldPointingLooksForTheLookTimeThenComesBackToThePoseItLeft)
{
    PointDirectorConfig config;
    config.look_s = 4.0;
    PointDirector director(config);
    FakeHead head;
    head.pose.pan_deg = 5.0;  // where the fixate law keeps the hand
    head.pose.tilt_deg = -2.0;
    const int pick_frame = 30;
    const Trace r = run(director, head, 12.0, [&](int i) {
        return i == pick_frame ? std::optional(aim_at(35.0, 10.0)) : std::nullopt;
    });
    ASSERT_EQ(count(r, PointStep::Kind::Aim), 1);
    ASSERT_EQ(count(r, PointStep::Kind::Return), 1);
    EXPECT_EQ(r.steps[pick_frame].kind, PointStep::Kind::Aim);
    EXPECT_EQ(r.steps[pick_frame - 1].kind, PointStep::Kind::Follow);
    // 30 deg at 60 deg/s: there after 0.5 s; it then stays for the look time.
    const auto ret = std::find_if(r.steps.begin(), r.steps.end(),
                                  [](const PointStep& s) { return s.kind == PointStep::Kind::Return; });
    const int return_frame = static_cast<int>(ret - r.steps.begin());
    EXPECT_NEAR((return_frame - pick_frame) / kFps, 0.5 + 4.0, 3.0 / kFps);
    for (int i = pick_frame + 20; i < return_frame; ++i) {
        EXPECT_NEAR(r.poses[i].pan_deg, 35.0, 1e-9) << i;
        EXPECT_EQ(r.steps[i].kind, PointStep::Kind::Hold) << i;
    }
    // Back where it left the hand, then following again.
    EXPECT_DOUBLE_EQ(ret->pose.pan_deg, 5.0);
    EXPECT_DOUBLE_EQ(ret->pose.tilt_deg, -2.0);
    EXPECT_NEAR(r.poses.back().pan_deg, 5.0, 1e-9);
    EXPECT_NEAR(r.poses.back().tilt_deg, -2.0, 1e-9);
    EXPECT_EQ(r.phases.back(), PointPhase::Following);
    EXPECT_EQ(r.steps.back().kind, PointStep::Kind::Follow);
}

TEST(PointDirector, NoPickMovesNothing)
{
    // A talking hand, a lowered hand: the dwell picks nothing, so the director only follows.
    PointDirector director;
    FakeHead head;
    const Trace r = run(director, head, 300.0, [](int) { return std::optional<PointAim>(); });
    EXPECT_EQ(count(r, PointStep::Kind::Follow), static_cast<int>(r.steps.size()));
}

TEST(PointDirector, ANewPickWhileLookingRetargetsAndTheReturnIsToTheFirstPose)
{
    PointDirectorConfig config;
    config.look_s = 2.0;
    PointDirector director(config);
    FakeHead head;
    head.pose.pan_deg = -3.0;
    const Trace r = run(director, head, 10.0, [](int i) {
        if (i == 10) return std::optional(aim_at(30.0, 0.0));
        if (i == 50) return std::optional(aim_at(-20.0, 5.0));  // while looking at the first
        return std::optional<PointAim>();
    });
    EXPECT_EQ(count(r, PointStep::Kind::Aim), 2);
    EXPECT_EQ(r.steps[50].kind, PointStep::Kind::Aim);
    EXPECT_DOUBLE_EQ(r.steps[50].aim.pan_deg, -20.0);
    // 50 deg at 60 deg/s, then the full look time at the new target.
    const auto ret = std::find_if(r.steps.begin(), r.steps.end(),
                                  [](const PointStep& s) { return s.kind == PointStep::Kind::Return; });
    ASSERT_NE(ret, r.steps.end());
    EXPECT_NEAR((ret - r.steps.begin() - 50) / kFps, 50.0 / 60.0 + 2.0, 3.0 / kFps);
    EXPECT_DOUBLE_EQ(ret->pose.pan_deg, -3.0);
    EXPECT_NEAR(r.poses.back().pan_deg, -3.0, 1e-9);
}

TEST(PointDirector, TheSamePointingStillHeldIsAnsweredOnceUntilTheHandIsLowered)
{
    PointDirectorConfig config;
    config.look_s = 1.0;
    config.lowered_s = 1.0;
    PointDirector director(config);
    FakeHead head;
    // The dwell picks the same target again after the look (it lost the hand while the head
    // looked away): that is the same pointing, held on.
    Trace r = run(director, head, 6.0, [](int i) {
        return (i == 10 || i == 120) ? std::optional(aim_at(20.0, 3.0)) : std::nullopt;
    });
    EXPECT_EQ(count(r, PointStep::Kind::Aim), 1);
    EXPECT_EQ(r.phases.back(), PointPhase::Following);
    // A pick elsewhere is a new pointing.
    r = run(director, head, 1.0, [](int i) { return i == 5 ? std::optional(aim_at(-25.0, 3.0)) : std::nullopt; });
    EXPECT_EQ(count(r, PointStep::Kind::Aim), 1);
    // After that look, the hand is lowered (tracked, no pointing) for longer than lowered_s:
    // pointing at the same place again looks again.
    run(director, head, 4.0, [](int) { return std::optional<PointAim>(); });
    ASSERT_EQ(director.phase(), PointPhase::Following);
    r = run(director, head, 1.5, [](int) { return std::optional<PointAim>(); }, /*pointing=*/false);
    r = run(director, head, 1.0, [](int i) { return i == 0 ? std::optional(aim_at(-25.0, 3.0)) : std::nullopt; });
    EXPECT_EQ(count(r, PointStep::Kind::Aim), 1);
}

}  // namespace
