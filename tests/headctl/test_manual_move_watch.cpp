// The manual-move watch on a fake clock: a head at rest where the link's commands left it is
// held there, and leaving that place is someone else's move; after a command that names where
// an axis goes, the old pose reported over a slow link is not taken for someone holding it.
#include "headctl/steering/manual_move_watch.hpp"

#include <gtest/gtest.h>

namespace gc::headctl {
namespace {

HeadState at(double pan_deg, double tilt_deg = 0.0, bool moving = false)
{
    HeadState s;
    s.pose.pan_deg = pan_deg;
    s.pose.tilt_deg = tilt_deg;
    s.moving[static_cast<std::size_t>(Axis::Pan)] = moving;
    return s;
}

HeadCommand absolute_pan_tilt(double pan_deg, double tilt_deg)
{
    HeadCommand c{CommandKind::Absolute, {}, 0};
    c.values.set(Axis::Pan, pan_deg);
    c.values.set(Axis::Tilt, tilt_deg);
    return c;
}

TEST(ManualMoveWatch, AHeadAtRestWhereItWasSentIsHeldThere)
{
    ManualMoveWatch watch;
    watch.commanded(absolute_pan_tilt(30.0, 5.0), 0.0);
    EXPECT_FALSE(watch.moved_by_someone_else(at(15.0, 2.0, true), 0.2));
    EXPECT_FALSE(watch.moved_by_someone_else(at(30.0, 5.0), 0.6));  // arrived: held here
    EXPECT_FALSE(watch.moved_by_someone_else(at(30.2, 5.0), 0.8));  // within the readings' wander
    EXPECT_TRUE(watch.moved_by_someone_else(at(34.0, 5.0), 1.0));
}

TEST(ManualMoveWatch, TheOldPoseOfASlowLinkIsNotSomeoneHoldingIt)
{
    ManualMoveWatch watch;
    watch.commanded(absolute_pan_tilt(30.0, 0.0), 0.0);
    // The camera reports its old pose, at rest, for a second before it starts.
    for (double t = 0.1; t < 1.0; t += 0.1) EXPECT_FALSE(watch.moved_by_someone_else(at(0.0), t));
    EXPECT_FALSE(watch.moved_by_someone_else(at(12.0, 0.0, true), 1.2));
    EXPECT_FALSE(watch.moved_by_someone_else(at(30.0), 1.8));
    EXPECT_TRUE(watch.moved_by_someone_else(at(20.0), 3.0));  // then a person turns it back
}

TEST(ManualMoveWatch, AMoveThatNeverArrivesIsHeldWhereItStopsAfterTheTimeout)
{
    ManualMoveWatch watch;
    watch.commanded(absolute_pan_tilt(30.0, 0.0), 0.0);
    EXPECT_FALSE(watch.moved_by_someone_else(at(8.0), 4.9));  // stopped short: not yet held
    EXPECT_FALSE(watch.moved_by_someone_else(at(8.0), 5.1));  // held at 8 deg from now on
    EXPECT_TRUE(watch.moved_by_someone_else(at(-5.0), 6.0));
}

TEST(ManualMoveWatch, HomeGoesToZeroAndAPresetOnlySettles)
{
    ManualMoveWatch watch;
    watch.commanded(HeadCommand{CommandKind::Home, {}, 0}, 0.0);
    EXPECT_FALSE(watch.moved_by_someone_else(at(40.0), 0.5));  // still where it was
    EXPECT_FALSE(watch.moved_by_someone_else(at(0.0), 1.5));
    EXPECT_TRUE(watch.moved_by_someone_else(at(3.0), 2.0));
    // A preset's pose is not known here: it is held where it first rests after settling.
    watch.commanded(preset_command(CommandKind::RecallPreset, 2), 3.0);
    EXPECT_FALSE(watch.moved_by_someone_else(at(17.0), 3.3));
    EXPECT_TRUE(watch.moved_by_someone_else(at(25.0), 3.6));
}

HeadState tilting(double tilt_deg)
{
    HeadState s = at(10.0, tilt_deg);
    s.moving[static_cast<std::size_t>(Axis::Tilt)] = true;
    return s;
}

TEST(ManualMoveWatch, AHeldAxisThatBeginsToMoveIsStirringUntilItLeavesOrSettles)
{
    ManualMoveWatch watch;
    watch.commanded(absolute_pan_tilt(10.0, 0.0), 0.0);
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 0.5));  // held at 10 deg, 0 deg
    EXPECT_FALSE(watch.stirring(Axis::Pan));
    // Someone begins to turn it: the first sample is still within the readings' wander.
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 1.0));
    EXPECT_TRUE(watch.stirring(Axis::Pan));
    EXPECT_FALSE(watch.stirring(Axis::Tilt));
    EXPECT_TRUE(watch.moved_by_someone_else(at(10.8, 0.0, true), 1.04));
    EXPECT_FALSE(watch.stirring(Axis::Pan));
    // A motion that stays within the tolerance past settle_s is the reading's noise.
    watch.reset();
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 1.5));
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 1.6));
    EXPECT_TRUE(watch.stirring(Axis::Pan));
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.2, 0.0, true), 1.86));
    EXPECT_FALSE(watch.stirring(Axis::Pan));
    // Tilt alike, each axis on its own.
    watch.reset();
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 2.0));
    EXPECT_FALSE(watch.moved_by_someone_else(tilting(0.2), 2.1));
    EXPECT_TRUE(watch.stirring(Axis::Tilt));
    EXPECT_FALSE(watch.stirring(Axis::Pan));
    EXPECT_FALSE(watch.stirring(Axis::Zoom));
    // A command of the link's own releases the axis: its motion is not stirring.
    watch.commanded(absolute_pan_tilt(20.0, 0.0), 2.15);
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 2.2));
    EXPECT_FALSE(watch.stirring(Axis::Pan));
}

TEST(ManualMoveWatch, AWobblingReadingStirsOnlyForItsFirstQuarterSecond)
{
    ManualMoveWatch watch;
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 0.0));  // held where it first rests
    // Flags that come and go every other sample (a reading one count apart) do not begin
    // the motion again: after settle_s it is noise, and steering goes on.
    for (int i = 1; i <= 20; ++i) {
        const double t = 0.02 * i;
        EXPECT_FALSE(watch.moved_by_someone_else(at(i % 2 ? 10.1 : 10.0, 0.0, i % 2 == 1), t));
        EXPECT_EQ(watch.stirring(Axis::Pan), i % 2 == 1 && t < 0.02 + 0.25) << "at " << t << " s";
    }
    // After a quarter of a second at rest a new motion begins.
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 0.6));
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 0.7));
    EXPECT_TRUE(watch.stirring(Axis::Pan));
    // A sample stamped before the motion began starts it again rather than holding it.
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 0.65));
    EXPECT_TRUE(watch.stirring(Axis::Pan));
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 0.8));
    EXPECT_TRUE(watch.stirring(Axis::Pan));
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.1, 0.0, true), 0.92));
    EXPECT_FALSE(watch.stirring(Axis::Pan));
    // At rest again, then flags on every other sample of a slow link (0.15 s apart): only
    // the first begins a motion.
    EXPECT_FALSE(watch.moved_by_someone_else(at(10.0), 1.0));
    for (int i = 1; i <= 6; ++i) {
        const double t = 1.15 + 0.15 * i;
        EXPECT_FALSE(watch.moved_by_someone_else(at(10.0, 0.0, i % 2 == 1), t));
        EXPECT_EQ(watch.stirring(Axis::Pan), i == 1) << "at " << t << " s";
    }
}

}  // namespace
}  // namespace gc::headctl
