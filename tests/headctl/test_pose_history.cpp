// Timestamped head states: interpolation at capture times, clamped extrapolation, the ring.
#include "headctl/pose_history.hpp"

#include <gtest/gtest.h>

namespace gc::headctl {
namespace {

using namespace std::chrono_literals;

StateSample sample(std::chrono::milliseconds t, double pan, double tilt = 0.0)
{
    StateSample s;
    s.time = t;
    s.state.pose.pan_deg = pan;
    s.state.pose.tilt_deg = tilt;
    s.state.moving = {true, true, true, true};
    return s;
}

TEST(PoseHistory, InterpolatesBetweenSamples)
{
    PoseHistory h(8);
    EXPECT_FALSE(h.pose_at(0ms, 100ms));
    h.push(sample(100ms, 0.0, 10.0));
    h.push(sample(200ms, 10.0, 0.0));
    h.push(sample(300ms, 10.0, 0.0));
    EXPECT_DOUBLE_EQ(h.pose_at(150ms, 0ms)->pan_deg, 5.0);
    EXPECT_DOUBLE_EQ(h.pose_at(125ms, 0ms)->tilt_deg, 7.5);
    EXPECT_DOUBLE_EQ(h.pose_at(200ms, 0ms)->pan_deg, 10.0);
    EXPECT_DOUBLE_EQ(h.pose_at(250ms, 0ms)->pan_deg, 10.0);
}

TEST(PoseHistory, ClampsBeforeTheFirstAndExtrapolatesBoundedlyAfterTheLast)
{
    PoseHistory h(8);
    h.push(sample(100ms, 0.0));
    EXPECT_DOUBLE_EQ(h.pose_at(500ms, 100ms)->pan_deg, 0.0);  // one sample: held
    h.push(sample(200ms, 10.0));                              // 100 deg/s
    EXPECT_DOUBLE_EQ(h.pose_at(50ms, 100ms)->pan_deg, 0.0);
    EXPECT_DOUBLE_EQ(h.pose_at(250ms, 100ms)->pan_deg, 15.0);
    EXPECT_DOUBLE_EQ(h.pose_at(300ms, 100ms)->pan_deg, 20.0);
    EXPECT_DOUBLE_EQ(h.pose_at(900ms, 100ms)->pan_deg, 20.0);  // clamped to 100 ms ahead
    EXPECT_DOUBLE_EQ(h.pose_at(900ms, 0ms)->pan_deg, 10.0);
    StateSample at_rest = sample(300ms, 11.0);
    at_rest.state.moving[0] = false;  // the head says pan has stopped: no extrapolation
    h.push(at_rest);
    EXPECT_DOUBLE_EQ(h.pose_at(350ms, 100ms)->pan_deg, 11.0);
}

TEST(PoseHistory, RingKeepsTheNewestAndDropsOutOfOrderSamples)
{
    PoseHistory h(4);
    for (int i = 0; i < 10; ++i) h.push(sample(std::chrono::milliseconds(i * 10), i));
    EXPECT_EQ(h.size(), 4u);
    EXPECT_DOUBLE_EQ(h.pose_at(0ms, 0ms)->pan_deg, 6.0);  // oldest kept is t=60 ms
    EXPECT_DOUBLE_EQ(h.pose_at(75ms, 0ms)->pan_deg, 7.5);
    h.push(sample(85ms, 100.0));  // older than the newest: dropped
    h.push(sample(90ms, 100.0));  // same time as the newest: dropped
    EXPECT_DOUBLE_EQ(h.newest()->state.pose.pan_deg, 9.0);
    EXPECT_THROW(PoseHistory(1), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl
