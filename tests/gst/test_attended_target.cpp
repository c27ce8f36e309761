// output=attended frames what a held pointing picked: within a second of the dwell's end,
// the crop centres on the point target-distance along the rendered hand's true ray, as wide
// as target-region, while the hand stays tracked, and an attended-target message announces
// the pick. A director camera (a simulated head on loopback, placed by the calibration file)
// turns and zooms to the same target. Lowering the hand is not needed here: the dwell's own rules are unit-tested
// (tests/stereo/test_pointing_dwell.cpp).
#include "gst_fixture.hpp"

#include "running_head.hpp"
#include "stereo/calibration_io.hpp"
#include "stereo/director_mount.hpp"

#include "sim/motion_script.hpp"
#include "stereo/calibration.hpp"
#include "stereo/pointing_dwell.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
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

// With target-plane set, the pick is where the hand's ray meets that plane: here a ceiling
// 600 mm above the head (y = -600 mm), some 590 mm along the rendered hand's upward ray, where
// target-distance (left at 2 m) would have put it 1.4 m farther.
TEST(AttendedTarget, ATargetPlaneHoldsThePickWhereTheRayMeetsIt)
{
    gc::test::init_gstreamer();
    const std::string eye = " motion=static num-buffers=90 ";
    const gc::test::RunResult r = gc::test::run_pipeline(
        "handscenesrc name=l eye=left" + eye + "! t.sink_left handscenesrc eye=right" + eye +
            "! t.sink_right handtracker name=t dwell=1.0 target-plane=\"<0, 1, 0, 600>\" ! fakesink sync=false",
        120 * GST_SECOND);
    ASSERT_TRUE(r.eos) << r.error;
    const auto picks = r.named("attended-target", "t");
    ASSERT_EQ(picks.size(), 1u);
    const auto truths = r.named("hand-truth", "l");
    ASSERT_FALSE(truths.empty());
    const cv::Vec3d tip = vec3(truths.back(), "fingertip-head-mm");
    const cv::Vec3d direction = vec3(truths.back(), "direction-head");
    ASSERT_LT(direction[1], -0.5) << "the scene's hand no longer points up";
    const cv::Vec3d on_ceiling = tip + ((-600.0 - tip[1]) / direction[1]) * direction;
    const cv::Vec3d picked = vec3(picks[0], "target-head-mm");
    EXPECT_NEAR(picked[1], -600.0, 1.0);
    // 3 deg of ray error at ~590 mm moves the point ~30 mm.
    EXPECT_LT(cv::norm(picked - on_ceiling), 60.0) << picked << " against " << on_ceiling;
}

// The director stands 1 m to the right of the head and 300 mm above it, turned 20 degrees to
// the left; the hand's pick, 300 mm along its ray, must end up in the middle third of its
// picture with the 500 mm region 75-125 % of its width, as the scene's truth places it.
TEST(AttendedTarget, AHeldPointingTurnsTheDirectorToItsTarget)
{
    gc::test::init_gstreamer();
    gc::DirectorMount mount;
    const cv::Matx33d turned = gc::rotation_about_y(-20.0).t();
    mount.head_to_base = {turned, -(turned * cv::Vec3d(1000.0, -300.0, 0.0))};
    gc::StereoCalibration cal = gc::default_calibration(cv::Size(640, 480));
    cal.director = mount;
    const std::string calibration =
        (std::filesystem::path(::testing::TempDir()) / ("director_" + std::to_string(::getpid()) + ".yml")).string();
    gc::save_calibration(cal, calibration);
    gc::loopback::RunningHead director(gc::loopback::loopback_head());

    const std::string eye = " motion=static num-buffers=" + std::to_string(kFrames) + " ";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "handscenesrc name=l eye=left" + eye + "truth-messages=true ! t.sink_left handscenesrc eye=right" + eye +
        "! t.sink_right handtracker name=t dwell=1.0 target-distance=300 target-region=500 calibration=" + calibration +
        " director=" + director.uri() + " ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 120 * GST_SECOND);
    std::filesystem::remove(calibration);
    ASSERT_TRUE(r.eos) << r.error;
    const auto picks = r.named("attended-target", "t");
    ASSERT_EQ(picks.size(), 1u);
    const auto truths = r.named("hand-truth", "l");
    ASSERT_FALSE(truths.empty());
    const cv::Vec3d target = vec3(truths.back(), "fingertip-head-mm") + 300.0 * vec3(truths.back(), "direction-head");

    // The head moves in real time: wait until it stands still, then look through it.
    std::optional<gc::DirectorPlacement> placed;
    gc::HeadPose pose;
    EXPECT_TRUE(gc::loopback::eventually(
        [&] {
            const gc::headctl::HeadState state = director.state();
            pose = state.pose;
            const bool moving = std::any_of(state.moving.begin(), state.moving.end(), [](bool m) { return m; });
            return !moving && pose.zoom > 1.0;
        },
        std::chrono::milliseconds(5000)));
    // The element said where it sent the director.
    const auto sent = r.named("director", "t");
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_STREQ(gst_structure_get_string(sent[0], "event"), "frame");
    double pan = 0.0, zoom = 0.0;
    EXPECT_TRUE(gst_structure_get_double(sent[0], "pan-deg", &pan));
    EXPECT_TRUE(gst_structure_get_double(sent[0], "zoom", &zoom));
    EXPECT_NEAR(pose.pan_deg, pan, 0.1);
    EXPECT_NEAR(pose.zoom, zoom, 0.01);
    placed = gc::place_in_director(mount, pose, target, 500.0);
    ASSERT_TRUE(placed);
    EXPECT_GT(placed->centre.x, 1.0 / 3) << "pan " << pose.pan_deg;
    EXPECT_LT(placed->centre.x, 2.0 / 3) << "pan " << pose.pan_deg;
    EXPECT_GT(placed->centre.y, 1.0 / 3) << "tilt " << pose.tilt_deg;
    EXPECT_LT(placed->centre.y, 2.0 / 3) << "tilt " << pose.tilt_deg;
    EXPECT_GE(placed->fill, 0.75) << "zoom " << pose.zoom;
    EXPECT_LE(placed->fill, 1.25) << "zoom " << pose.zoom;
}

}  // namespace
