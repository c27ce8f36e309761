// The simulated head's mechanics, driven by a fake clock.
#include "headctl/sim/head_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gc::headctl {
namespace {

AxisValues pan(double v)
{
    AxisValues a;
    a.set(Axis::Pan, v);
    return a;
}

TEST(HeadModel, TrapezoidalMoveRespectsVelocityAndAccelerationLimits)
{
    HeadModelConfig config;  // pan: 120 deg/s, 400 deg/s^2
    HeadModel head(config);
    head.move_absolute(pan(90.0), 0.0);
    double previous_pos = 0.0;
    double previous_vel = 0.0;
    double peak = 0.0;
    double t_arrive = -1.0;
    for (int i = 1; i <= 2000; ++i) {
        const double t = i * 0.001;
        const HeadState s = head.state(t);
        const double vel = (s.pose.pan_deg - previous_pos) / 0.001;
        EXPECT_LE(std::abs(vel), 120.0 + 1e-6) << t;
        if (i > 1) {
            EXPECT_LE(std::abs(vel - previous_vel), 400.0 * 0.001 * 2 + 1e-6) << t;
        }
        EXPECT_LE(s.pose.pan_deg, 90.0 + 1e-9) << "overshoot at " << t;
        peak = std::max(peak, std::abs(vel));
        if (t_arrive < 0 && !s.moving[0]) t_arrive = t;
        previous_pos = s.pose.pan_deg;
        previous_vel = vel;
    }
    EXPECT_NEAR(peak, 120.0, 1.0);
    // Ideal trapezoid: 0.3 s ramp up (18 deg), 54 deg cruise (0.45 s), 0.3 s ramp down: 1.05 s.
    EXPECT_NEAR(t_arrive, 1.05, 0.03);
    EXPECT_DOUBLE_EQ(head.state(3.0).pose.pan_deg, 90.0);
}

AxisValues zoom(double v)
{
    AxisValues a;
    a.set(Axis::Zoom, v);
    return a;
}

TEST(HeadModel, ZoomIsAMagnificationWithItsOwnLimitsAndSpeed)
{
    HeadModel head(HeadModelConfig{});  // zoom: 1..20, 8 per s, 30 per s^2
    EXPECT_DOUBLE_EQ(head.state(0.0).pose.zoom, 1.0);
    EXPECT_THROW(head.move_absolute(zoom(0.5), 0.0), std::out_of_range);
    EXPECT_THROW(head.move_absolute(zoom(21.0), 0.0), std::out_of_range);
    EXPECT_THROW(head.move_velocity(zoom(9.0), 0.0), std::out_of_range);
    head.move_absolute(zoom(2.0), 0.0);
    const HeadState early = head.state(0.1);  // at 30 per s^2: 0.15 after 0.1 s
    EXPECT_NEAR(early.pose.zoom, 1.15, 0.01);
    EXPECT_TRUE(early.moving_axis(Axis::Zoom));
    EXPECT_FALSE(early.moving_axis(Axis::Pan));
    const HeadState there = head.state(2.0);
    EXPECT_DOUBLE_EQ(there.pose.zoom, 2.0);
    EXPECT_FALSE(there.moving_axis(Axis::Zoom));
    // From 1 to 20 the lens reaches its 8 per s.
    head.move_absolute(zoom(20.0), 2.0);
    const double cruising = head.state(2.0 + 8.0 / 30.0).pose.zoom;
    EXPECT_NEAR(head.state(3.0 + 8.0 / 30.0).pose.zoom - cruising, 8.0, 0.05);
    head.home(10.0);
    EXPECT_DOUBLE_EQ(head.state(20.0).pose.zoom, 1.0);
}

TEST(HeadModel, APresetKeepsWhereTheHeadWasAndRecallsIt)
{
    HeadModel head(HeadModelConfig{});
    EXPECT_THROW(head.recall_preset(3, 0.0), std::out_of_range);
    AxisValues there = pan(30.0);
    there.set(Axis::Tilt, -10.0);
    there.set(Axis::Zoom, 4.0);
    head.move_absolute(there, 0.0);
    head.save_preset(3, 5.0);
    head.home(5.0);
    EXPECT_DOUBLE_EQ(head.state(10.0).pose.pan_deg, 0.0);
    head.recall_preset(3, 10.0);
    const HeadPose back = head.state(15.0).pose;
    EXPECT_DOUBLE_EQ(back.pan_deg, 30.0);
    EXPECT_DOUBLE_EQ(back.tilt_deg, -10.0);
    EXPECT_DOUBLE_EQ(back.zoom, 4.0);
    head.move_absolute(pan(-20.0), 15.0);
    head.save_preset(3, 20.0);  // saving again replaces it
    head.home(20.0);
    head.recall_preset(3, 25.0);
    EXPECT_DOUBLE_EQ(head.state(30.0).pose.pan_deg, -20.0);
}

TEST(HeadModel, ZoomLimitsMustHoldTheWidestView)
{
    HeadModelConfig config;
    config.limits[Axis::Zoom] = AxisLimits{0.5, 4.0, 1.0, 1.0};
    EXPECT_THROW(config.validate(), std::invalid_argument);
    config.limits[Axis::Zoom] = AxisLimits{2.0, 4.0, 1.0, 1.0};
    EXPECT_THROW(config.validate(), std::invalid_argument);
}

TEST(HeadModel, RejectsTargetsBeyondSoftLimitsAndTooFastVelocities)
{
    HeadModel head(HeadModelConfig{});
    EXPECT_THROW(head.move_absolute(pan(170.5), 0.0), std::out_of_range);
    EXPECT_THROW(head.move_velocity(pan(121.0), 0.0), std::out_of_range);
    head.move_absolute(pan(160.0), 0.0);
    EXPECT_THROW(head.move_relative(pan(20.0), 0.0), std::out_of_range);  // relative to the commanded 160
    head.move_relative(pan(-10.0), 0.0);
    EXPECT_DOUBLE_EQ(head.state(5.0).pose.pan_deg, 150.0);
}

TEST(HeadModel, VelocityMoveBrakesToAStopAtTheSoftLimit)
{
    HeadModelConfig config;
    config.velocity_timeout_s = 0.0;
    HeadModel head(config);
    head.move_velocity(pan(120.0), 0.0);
    double max_seen = 0.0;
    for (int i = 1; i <= 4000; ++i) max_seen = std::max(max_seen, head.state(i * 0.001).pose.pan_deg);
    EXPECT_LE(max_seen, 170.0);
    EXPECT_NEAR(head.state(4.0).pose.pan_deg, 170.0, 0.05);
    EXPECT_FALSE(head.state(4.1).moving[0]);
}

TEST(HeadModel, VelocityMoveStopsWhenNotRenewed)
{
    HeadModelConfig config;
    config.velocity_timeout_s = 0.5;
    HeadModel head(config);
    head.move_velocity(pan(20.0), 0.0);
    const double at_timeout = head.state(0.5).pose.pan_deg;
    const HeadState later = head.state(2.0);
    EXPECT_FALSE(later.moving[0]);
    // Brakes from 20 deg/s at 400 deg/s^2: 0.5 deg more at most.
    EXPECT_NEAR(later.pose.pan_deg, at_timeout + 0.5, 0.05);
}

TEST(HeadModel, StopHomeAndLatency)
{
    HeadModelConfig config;
    config.latency_s = 0.1;
    HeadModel head(config);
    head.move_absolute(pan(30.0), 0.0);
    EXPECT_DOUBLE_EQ(head.state(0.099).pose.pan_deg, 0.0);  // not yet in effect
    EXPECT_GT(head.state(0.2).pose.pan_deg, 0.0);
    head.stop(0.2);
    const double stopped = head.state(1.0).pose.pan_deg;
    EXPECT_LT(stopped, 30.0);
    EXPECT_FALSE(head.state(1.0).moving[0]);
    head.home(1.0);
    EXPECT_DOUBLE_EQ(head.state(3.0).pose.pan_deg, 0.0);
    EXPECT_EQ(head.state(3.0).server_time_us, 3000000);
}

TEST(HeadModel, AngleErrorIsSeededAndBounded)
{
    HeadModelConfig config;
    config.angle_error_deg = 0.2;
    config.seed = 42;
    auto reached = [&](std::uint64_t seed) {
        config.seed = seed;
        HeadModel head(config);
        head.move_absolute(pan(10.0), 0.0);
        return head.state(2.0).pose.pan_deg;
    };
    EXPECT_DOUBLE_EQ(reached(42), reached(42));
    EXPECT_NE(reached(42), reached(43));
    EXPECT_NEAR(reached(42), 10.0, 1.0);
    EXPECT_NE(reached(42), 10.0);
}

TEST(HeadModel, ValidatesItsConfiguration)
{
    HeadModelConfig config;
    config.latency_s = -1.0;
    EXPECT_THROW(HeadModel{config}, std::invalid_argument);
    config = {};
    config.limits[Axis::Tilt].max_acceleration_dps2 = 0.0;
    EXPECT_THROW(HeadModel{config}, std::invalid_argument);
    config = {};
    config.limits[Axis::Pan].min_deg = 10.0;  // home outside the limits
    EXPECT_THROW(HeadModel{config}, std::invalid_argument);
    HeadModel head(HeadModelConfig{});
    EXPECT_THROW(head.state(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl
