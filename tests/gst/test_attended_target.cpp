// output=attended frames what a held pointing picked: within a second of the dwell's end,
// the crop centres on the point target-distance along the rendered hand's true ray, as wide
// as target-region, while the hand stays tracked, and an attended-target message announces
// the pick. Lowering the hand is not needed here: the dwell's own rules are unit-tested
// (tests/stereo/test_pointing_dwell.cpp).
#include "gst_fixture.hpp"

#include "sim/motion_script.hpp"
#include "stereo/calibration.hpp"
#include "stereo/pointing_dwell.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace {

constexpr int kFrames = 150;
constexpr double kFps = 30.0;

GstPadProbeReturn capture_meta(GstPad*, GstPadProbeInfo* info, gpointer data)
{
    auto* metas = static_cast<std::vector<GstHandPointingMeta>*>(data);
    if (const GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(GST_PAD_PROBE_INFO_BUFFER(info)))
        metas->push_back(*meta);
    return GST_PAD_PROBE_OK;
}

cv::Vec3d vec3(const GstStructure* s, const char* field)
{
    const GValue* v = gst_structure_get_value(s, field);
    EXPECT_NE(v, nullptr) << field;
    cv::Vec3d out;
    for (guint i = 0; v && i < 3; ++i) out[int(i)] = g_value_get_double(gst_value_array_get_value(v, i));
    return out;
}

TEST(AttendedTarget, AHeldPointingIsFramedWithinASecondOfTheDwell)
{
    gc::test::init_gstreamer();
    // The rendered hand points up and to the left; 200 mm along its ray stays in view.
    const std::string eye = " motion=static num-buffers=" + std::to_string(kFrames) + " ";
    gc::test::ElementPtr pipeline =
        gc::test::parse_pipeline("handscenesrc name=l eye=left" + eye + "! t.sink_left handscenesrc eye=right" + eye +
                                 "! t.sink_right "
                                 "handtracker name=t output=attended dwell=1.0 target-distance=200 target-region=500 ! "
                                 "video/x-raw,width=640,height=360 ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    std::vector<GstHandPointingMeta> metas;
    gc::test::probe_buffers(pipeline.get(), "t", "src", capture_meta, &metas);
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 120 * GST_SECOND);
    ASSERT_TRUE(r.eos) << r.error;
    ASSERT_EQ(metas.size(), size_t(kFrames));

    const gc::StereoCalibration cal = gc::default_calibration(cv::Size(640, 480));
    std::map<guint64, const GstStructure*> truth;
    for (const GstStructure* t : r.named("hand-truth", "l")) {
        guint64 frame = 0;
        gst_structure_get_uint64(t, "frame", &frame);
        truth[frame] = t;
    }
    int tracked = 0, first_pointing = -1, framed_from = -1;
    for (int i = 0; i < kFrames; ++i) {
        const GstHandPointingMeta& m = metas[size_t(i)];
        tracked += m.state == GST_HAND_POINTING_STATE_TRACKING;
        if (first_pointing < 0 && (m.flags & GST_HAND_POINTING_FLAG_HAS_3D)) first_pointing = i;
        ASSERT_TRUE(truth.count(guint64(i)));
        const cv::Vec3d target =
            vec3(truth[guint64(i)], "fingertip-head-mm") + 200.0 * vec3(truth[guint64(i)], "direction-head");
        const auto region = gc::region_in_left_view(target, 500.0, cal, gc::HeadPose{});
        ASSERT_TRUE(region);
        const double dx = (region->centre.x - m.view_x) / m.view_width;
        const double dy = (region->centre.y - m.view_y) / m.view_height;
        const double fill = region->width_px / m.view_width;
        const bool framed =
            dx > 1.0 / 3 && dx < 2.0 / 3 && dy > 1.0 / 3 && dy < 2.0 / 3 && fill >= 0.75 && fill <= 1.25;
        if (framed && framed_from < 0) framed_from = i;
        if (!framed) framed_from = -1;  // framed means framed on every frame since
    }
    EXPECT_GE(tracked, kFrames * 95 / 100);
    ASSERT_GE(first_pointing, 0);
    ASSERT_GE(framed_from, 0) << "never framed for good";
    // The pick is announced: one attended-target message, on the frame the dwell ended: at
    // least a second after the first pointing, and within a second of the end of the wave
    // the scene's hand gives first (the ray moves while it waves).
    const auto picks = r.named("attended-target", "t");
    ASSERT_EQ(picks.size(), 1u);
    EXPECT_STREQ(gst_structure_get_string(picks[0], "event"), "picked");
    guint64 pick_frame = 0;
    ASSERT_TRUE(gst_structure_get_uint64(picks[0], "frame", &pick_frame));
    EXPECT_GE(int(pick_frame), first_pointing + int(1.0 * kFps) - 1);
    const int wave_end = int(gc::sim::MotionScript::kWaveSeconds * kFps);
    EXPECT_LE(int(pick_frame), std::max(first_pointing, wave_end) + int(1.0 * kFps) + 1)
        << "first pointing at " << first_pointing;
    // Framed within 1 s of the dwell's end, and not before it.
    EXPECT_LE(framed_from, int(pick_frame) + int(1.0 * kFps)) << "picked at " << pick_frame;
    EXPECT_GE(framed_from, int(pick_frame)) << "framed before the dwell ended";
    EXPECT_NE(gst_structure_get_value(picks[0], "target-head-mm"), nullptr);
}

}  // namespace
