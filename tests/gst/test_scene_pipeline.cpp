// handscenesrc x2 -> handtracker: every output buffer carries the meta, the hand-pointing
// message repeats it with timestamps, and both agree with the scene's ground truth; the
// same frames packed side by side on the `sink` pad give exactly the same tracking.
#include "gst_fixture.hpp"

#include <gst/app/gstappsrc.h>
#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/gstvideometa.h>
#include <gst/video/video.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace {

constexpr int kFrames = 90;

struct Captured {
    std::vector<GstHandPointingMeta> metas;
    int with_roi = 0;
    int roi_with_params = 0;
};

GstPadProbeReturn capture_meta(GstPad*, GstPadProbeInfo* info, gpointer data)
{
    auto* captured = static_cast<Captured*>(data);
    GstBuffer* buffer = GST_PAD_PROBE_INFO_BUFFER(info);
    if (const GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(buffer)) captured->metas.push_back(*meta);
    if (GstVideoRegionOfInterestMeta* roi = gst_buffer_get_video_region_of_interest_meta(buffer)) {
        ++captured->with_roi;
        EXPECT_EQ(roi->roi_type, g_quark_from_string("hand"));
        if (gst_video_region_of_interest_meta_get_param(roi, "hand-pointing")) ++captured->roi_with_params;
    }
    return GST_PAD_PROBE_OK;
}

std::string scene_sources(const std::string& extra)
{
    const std::string common = " scene=light motion=translate seed=3 num-buffers=" + std::to_string(kFrames) + " ";
    return "handscenesrc name=l eye=left" + common + extra +
           " ! t.sink_left "
           "handscenesrc name=r eye=right" +
           common + extra + " ! t.sink_right ";
}

TEST(ScenePipeline, MetaAndMessagesFollowTheGroundTruth)
{
    gc::test::init_gstreamer();
    // dwell=60: no pointing is held long enough to pick a target in these 3 s, so the attended
    // view keeps framing the hand and every tracked frame carries its region of interest.
    gc::test::ElementPtr pipeline =
        gc::test::parse_pipeline(scene_sources("") + "handtracker name=t draw=true output=attended dwell=60 ! "
                                                     "video/x-raw,width=320,height=240 ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    Captured captured;
    gc::test::probe_buffers(pipeline.get(), "t", "src", capture_meta, &captured);

    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND);
    ASSERT_TRUE(r.eos) << r.error;
    const auto messages = r.named("hand-pointing", "t");
    const auto truths = r.named("hand-truth", "l");
    ASSERT_EQ(captured.metas.size(), size_t(kFrames));
    ASSERT_EQ(messages.size(), size_t(kFrames));
    ASSERT_EQ(truths.size(), size_t(kFrames));

    std::map<guint64, const GstStructure*> truth_of;
    for (const GstStructure* t : truths) {
        guint64 frame = 0;
        ASSERT_TRUE(gst_structure_get_uint64(t, "frame", &frame));
        truth_of[frame] = t;
    }
    int tracked = 0;
    int with_3d = 0;
    std::vector<double> errors;
    for (int i = 0; i < kFrames; ++i) {
        const GstHandPointingMeta& meta = captured.metas[size_t(i)];
        const GstStructure* msg = messages[size_t(i)];
        EXPECT_EQ(meta.frame, guint64(i));
        EXPECT_NE(meta.flags & GST_HAND_POINTING_FLAG_STEREO, 0u);
        EXPECT_EQ(meta.flags & GST_HAND_POINTING_FLAG_INCOMPLETE, 0u);
        EXPECT_EQ(meta.flags & GST_HAND_POINTING_FLAG_FULL_VIEW, 0u);  // attended crop
        EXPECT_GT(meta.view_width, 0);
        // The message repeats the meta, with the buffer's times.
        guint64 frame = 0, running = 0, stream = 0;
        ASSERT_TRUE(gst_structure_get_uint64(msg, "frame", &frame));
        EXPECT_EQ(frame, meta.frame);
        ASSERT_TRUE(gst_structure_get_uint64(msg, "running-time", &running));
        ASSERT_TRUE(gst_structure_get_uint64(msg, "stream-time", &stream));
        EXPECT_EQ(running, gst_util_uint64_scale(guint64(i), GST_SECOND, 30));
        EXPECT_STREQ(gst_structure_get_string(msg, "state"), gst_hand_pointing_state_to_string(meta.state));
        const GstStructure* left = gc::test::get_child(msg, "left");
        ASSERT_NE(left, nullptr);
        EXPECT_EQ(gc::test::get_double(left, "x"), meta.left.x);
        EXPECT_EQ(gc::test::get_double(left, "fingertip-y"), meta.left.fingertip_y);
        EXPECT_EQ(gc::test::get_child(msg, "pointing") != nullptr, (meta.flags & GST_HAND_POINTING_FLAG_HAS_3D) != 0);

        const GstStructure* truth = truth_of[guint64(i)];
        ASSERT_NE(truth, nullptr);
        gboolean visible = FALSE;
        gst_structure_get_boolean(truth, "visible", &visible);
        if (meta.left.state == GST_HAND_POINTING_STATE_TRACKING && visible) {
            ++tracked;
            errors.push_back(std::hypot(meta.left.x - gc::test::get_double(truth, "palm-x"),
                                        meta.left.y - gc::test::get_double(truth, "palm-y")));
        }
        if (meta.flags & GST_HAND_POINTING_FLAG_HAS_3D) {
            ++with_3d;
            EXPECT_TRUE(std::isfinite(meta.azimuth_deg));
            EXPECT_GT(meta.palm_mm[2], 200.0);   // in front of the cameras,
            EXPECT_LT(meta.palm_mm[2], 3000.0);  // about a metre away in the scene
        }
    }
    // After the initial wave the hand is found and followed in most frames, near the truth.
    EXPECT_GE(tracked, kFrames / 2) << "tracked frames";
    EXPECT_GT(with_3d, 0);
    ASSERT_FALSE(errors.empty());
    std::nth_element(errors.begin(), errors.begin() + long(errors.size() / 2), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 25.0) << "median palm error, pixels";
    EXPECT_GE(captured.with_roi, tracked);
    EXPECT_EQ(captured.roi_with_params, captured.with_roi);
}

// handscenesrc x2 at 1280x720 -> handtracker tracking-width=W: the metas and the left
// view's truth.
struct HdRun {
    Captured captured;
    std::vector<const GstStructure*> truths;
    gc::test::RunResult result;
};

void run_hd(int tracking_width, HdRun& run)
{
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        scene_sources("! video/x-raw,width=1280,height=720") +
        "handtracker name=t tracking-width=" + std::to_string(tracking_width) + " ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    gc::test::probe_buffers(pipeline.get(), "t", "src", capture_meta, &run.captured);
    run.result = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND);
    ASSERT_TRUE(run.result.eos) << run.result.error;
    run.truths = run.result.named("hand-truth", "l");
    ASSERT_EQ(run.captured.metas.size(), size_t(kFrames));
    ASSERT_EQ(run.truths.size(), size_t(kFrames));
}

// HD views tracked at 640 wide (tracking-width): the meta still speaks in the views' own
// pixels, near the rendered truth, and differs from tracking at the views' size.
TEST(ScenePipeline, HdViewsTrackedNarrowerReportInTheirOwnPixels)
{
    gc::test::init_gstreamer();
    HdRun narrow, full;
    ASSERT_NO_FATAL_FAILURE(run_hd(640, narrow));
    ASSERT_NO_FATAL_FAILURE(run_hd(0, full));
    std::vector<double> errors;
    int with_3d = 0, differing = 0;
    for (int i = 0; i < kFrames; ++i) {
        const GstHandPointingMeta& meta = narrow.captured.metas[size_t(i)];
        EXPECT_EQ(meta.view_width, 1280);
        EXPECT_EQ(meta.view_height, 720);
        gboolean visible = FALSE;
        const GstStructure* truth = narrow.truths[size_t(i)];
        gst_structure_get_boolean(truth, "visible", &visible);
        if (meta.left.state == GST_HAND_POINTING_STATE_TRACKING && visible)
            errors.push_back(std::hypot(meta.left.fingertip_x - gc::test::get_double(truth, "fingertip-x"),
                                        meta.left.fingertip_y - gc::test::get_double(truth, "fingertip-y")));
        with_3d += (meta.flags & GST_HAND_POINTING_FLAG_HAS_3D) ? 1 : 0;
        differing += meta.left.fingertip_x != full.captured.metas[size_t(i)].left.fingertip_x ? 1 : 0;
    }
    ASSERT_GE(errors.size(), size_t(kFrames / 2)) << "tracked frames";
    std::nth_element(errors.begin(), errors.begin() + long(errors.size() / 2), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 25.0) << "median fingertip error, pixels of the 1280x720 views";
    EXPECT_GT(with_3d, 0);
    EXPECT_GT(differing, kFrames / 2) << "tracking-width changed nothing";
}

// The two views of the scene, pulled from handscenesrc into memory.
std::vector<gc::test::SamplePtr> render_eye(const char* eye)
{
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        std::string("handscenesrc scene=light motion=translate seed=3 truth-messages=false num-buffers=") +
        std::to_string(kFrames) + " eye=" + eye +
        " ! video/x-raw,format=BGR ! appsink name=out sync=false wait-on-eos=false");
    std::vector<gc::test::SamplePtr> samples;
    if (!pipeline) return samples;
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND,
                                                         [&] { samples = gc::test::drain(pipeline.get(), "out"); });
    EXPECT_TRUE(r.eos) << r.error;
    return samples;
}

TEST(ScenePipeline, SideBySideFramesTrackLikeTwoViews)
{
    gc::test::init_gstreamer();
    const std::string dir = gc::test::build_dir() + "/tests/gst";
    const std::string two_views = dir + "/two_views.jsonl";
    const std::string packed = dir + "/side_by_side.jsonl";

    const gc::test::RunResult a = gc::test::run_pipeline(
        scene_sources("truth-messages=false") + "handtracker name=t message-updates=none json-location=" + two_views +
        " ! fakesink sync=false");
    ASSERT_TRUE(a.eos) << a.error;

    const auto left = render_eye("left");
    const auto right = render_eye("right");
    ASSERT_EQ(left.size(), size_t(kFrames));
    ASSERT_EQ(right.size(), size_t(kFrames));
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "appsrc name=in format=time caps=\"video/x-raw,format=BGR,width=1280,height=480,framerate=30/1,"
        "multiview-mode=side-by-side\" ! t.sink handtracker name=t message-updates=none json-location=" +
        packed + " ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    GstElement* in = gst_bin_get_by_name(GST_BIN(pipeline.get()), "in");
    ASSERT_EQ(gst_element_set_state(pipeline.get(), GST_STATE_PAUSED), GST_STATE_CHANGE_ASYNC);
    for (int i = 0; i < kFrames; ++i) {
        GstBuffer* l = gst_sample_get_buffer(left[size_t(i)].get());
        GstBuffer* r = gst_sample_get_buffer(right[size_t(i)].get());
        GstMapInfo lm, rm, om;
        GstBuffer* out = gst_buffer_new_allocate(nullptr, 1280 * 480 * 3, nullptr);
        gst_buffer_map(l, &lm, GST_MAP_READ);
        gst_buffer_map(r, &rm, GST_MAP_READ);
        gst_buffer_map(out, &om, GST_MAP_WRITE);
        for (int y = 0; y < 480; ++y) {
            std::copy_n(lm.data + y * 640 * 3, 640 * 3, om.data + y * 1280 * 3);
            std::copy_n(rm.data + y * 640 * 3, 640 * 3, om.data + y * 1280 * 3 + 640 * 3);
        }
        gst_buffer_unmap(out, &om);
        gst_buffer_unmap(r, &rm);
        gst_buffer_unmap(l, &lm);
        GST_BUFFER_PTS(out) = GST_BUFFER_PTS(l);
        GST_BUFFER_DURATION(out) = GST_BUFFER_DURATION(l);
        ASSERT_EQ(gst_app_src_push_buffer(GST_APP_SRC(in), out), GST_FLOW_OK);
    }
    gst_app_src_end_of_stream(GST_APP_SRC(in));
    gst_object_unref(in);
    const gc::test::RunResult b = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND);
    ASSERT_TRUE(b.eos) << b.error;

    const auto expected = gc::test::read_lines(two_views);
    const auto actual = gc::test::read_lines(packed);
    ASSERT_EQ(expected.size(), size_t(kFrames));
    ASSERT_EQ(actual.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(actual[i], expected[i]) << "frame " << i;
}

// gesture-cycle=1 with gesture=open: the truth shows the open hand for a second, then the
// pointing hand, then the open hand again; the tracker's meta calls the open hand's frames
// pointing only where the model has not yet looked at the changed hand.
TEST(ScenePipeline, GestureCycleReachesTheTruthAndTheTracker)
{
    gc::test::init_gstreamer();
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        scene_sources("gesture=open gesture-cycle=1") +
        "handtracker name=t message-updates=none ! video/x-raw,width=320,height=240 ! fakesink sync=false");
    ASSERT_TRUE(pipeline);
    Captured captured;
    gc::test::probe_buffers(pipeline.get(), "t", "src", capture_meta, &captured);
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND);
    ASSERT_TRUE(r.eos) << r.error;
    std::map<guint64, std::string> gesture_of;
    for (const GstStructure* t : r.named("hand-truth", "l")) {
        guint64 frame = 0;
        gst_structure_get_uint64(t, "frame", &frame);
        const gchar* g = gst_structure_get_string(t, "gesture");
        gesture_of[frame] = g ? g : "";
    }
    ASSERT_EQ(gesture_of.size(), size_t(kFrames));
    for (const auto& [frame, gesture] : gesture_of)
        EXPECT_EQ(gesture, frame / 30 == 1 ? "pointing" : "open") << "frame " << frame;
    ASSERT_EQ(captured.metas.size(), size_t(kFrames));
    int open_tracked = 0, open_pointing = 0, pointing_tracked = 0, pointing_pointing = 0;
    for (int i = 0; i < kFrames; ++i) {
        const GstHandPointingMeta& m = captured.metas[i];
        if (m.left_gesture == GST_HAND_POINTING_GESTURE_UNKNOWN) continue;
        const bool says_pointing = m.left_gesture == GST_HAND_POINTING_GESTURE_POINTING;
        if (gesture_of[i] == "open") {
            ++open_tracked;
            open_pointing += says_pointing;
        } else {
            ++pointing_tracked;
            pointing_pointing += says_pointing;
        }
    }
    std::printf("open frames: %d with a gesture, %d of them pointing; pointing frames: %d with a gesture, %d "
                "pointing\n",
                open_tracked, open_pointing, pointing_tracked, pointing_pointing);
    EXPECT_GE(open_tracked, 40);
    EXPECT_LE(open_pointing, 0.15 * open_tracked);
    EXPECT_GE(pointing_pointing, 0.5 * pointing_tracked);
}

// Pixels of the overlay's marginal colour (BGR 255, 160, 0) in the bottom and right bands of
// the last output frame of a mono pipeline (only sink_left linked).
int marginal_pixels_in_mono_output(bool draw)
{
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "handscenesrc eye=left scene=clean motion=translate seed=3 truth-messages=false num-buffers=40 ! "
        "t.sink_left handtracker name=t message-updates=none draw=" +
        std::string(draw ? "true" : "false") +
        " ! video/x-raw,format=BGR,width=640,height=480 ! appsink name=out sync=false wait-on-eos=false");
    if (!pipeline) return -1;
    std::vector<gc::test::SamplePtr> samples;
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND,
                                                         [&] { samples = gc::test::drain(pipeline.get(), "out"); });
    EXPECT_TRUE(r.eos) << r.error;
    if (samples.empty()) return -1;
    GstBuffer* last = gst_sample_get_buffer(samples.back().get());
    GstMapInfo m;
    if (!gst_buffer_map(last, &m, GST_MAP_READ)) return -1;
    int count = 0;
    for (int y = 0; y < 480; ++y)
        for (int x = 0; x < 640; ++x) {
            if (y < 400 && x < 560) continue;
            const guint8* p = m.data + (y * 640 + x) * 3;
            count += p[0] == 255 && p[1] == 160 && p[2] == 0;
        }
    gst_buffer_unmap(last, &m);
    return count;
}

TEST(ScenePipeline, MonoInputDrawsTheParticleMarginals)
{
    gc::test::init_gstreamer();
    EXPECT_EQ(marginal_pixels_in_mono_output(false), 0);
    EXPECT_GT(marginal_pixels_in_mono_output(true), 50);
}

}  // namespace
