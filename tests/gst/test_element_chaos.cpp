// The pipeline handscenesrc x2 -> handtracker (steer off, JSON lines) while the rig's pose
// jumps: it runs to EOS without an error, and after each jump that leaves the hand in both
// views for 60 frames the tracker has it again within 30 frames (the long random run is
// the element_chaos benchmark).
#include "element_chaos.hpp"
#include "gst_fixture.hpp"

#include <glib/gstdio.h>
#include <unistd.h>

#include <string>
#include <vector>

namespace {

constexpr int kFrames = 300;

// Small turns the hand stays in view through, and one far enough that it leaves the view.
const std::vector<gc::chaos::RigJump> kJumps = {{40, 4.0, -3.0}, {110, 40.0, 0.0}, {150, -3.0, 2.0}, {230, 1.0, 5.0}};

TEST(ElementChaos, TheTrackerFindsTheHandAgainAfterEachJump)
{
    gc::test::init_gstreamer();
    const std::string json = gc::test::build_dir() + "/element-chaos-" + std::to_string(getpid()) + ".jsonl";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(gc::chaos::pipeline_description(kFrames, 1, json));
    ASSERT_TRUE(pipeline);
    ASSERT_TRUE(gc::chaos::drive_rig(pipeline.get(), kJumps));
    const gc::chaos::Run run = gc::chaos::play(pipeline.get(), {}, 120 * GST_SECOND);
    const std::vector<gc::chaos::Tracked> tracked = gc::chaos::read_tracked(json, run);
    g_remove(json.c_str());
    ASSERT_TRUE(run.eos) << run.error;
    EXPECT_EQ(run.error, "");
    ASSERT_EQ(tracked.size(), size_t(kFrames));
    ASSERT_EQ(run.left.size(), size_t(kFrames));
    ASSERT_EQ(run.right.size(), size_t(kFrames));
    // The far turn takes the hand out of view: the rig did move.
    EXPECT_FALSE(run.left[120].visible && run.right[120].visible);

    int judged = 0;
    for (const gc::chaos::Outcome& o : gc::chaos::judge(kJumps, run, tracked)) {
        if (!o.judged()) continue;
        ++judged;
        EXPECT_TRUE(o.found()) << "jump at frame " << o.frame << ": found after " << o.found_after << " frames";
    }
    EXPECT_GE(judged, 3);
}

}  // namespace
