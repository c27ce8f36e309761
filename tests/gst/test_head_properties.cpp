// The head properties of handtracker and handscenesrc: defaults, a bad URI refused at start
// with its reason, and heads that cannot be reached, never answer or answer garbage: the
// pipeline runs to its end with the same tracking as without a head, with one warning.
#include "fake_heads.hpp"
#include "gst_fixture.hpp"

#include <glib/gstdio.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using gc::test::ElementPtr;

constexpr int kFrames = 45;

std::string temp_path(const char* name)
{
    return std::string(g_get_tmp_dir()) + "/gesturecam-" + std::to_string(getpid()) + "-" + name;
}

struct TrackRun {
    gc::test::RunResult bus;
    std::vector<std::string> json;
    double seconds = 0.0;
};

// scene -> handtracker -> fakesink; the tracker's JSON lines and the bus.
TrackRun track(const std::string& head_uri, int frames = kFrames, bool live = false)
{
    const std::string json = temp_path("head.jsonl");
    const std::string common = std::string(" scene=light motion=translate seed=3 truth-messages=false is-live=") +
                               (live ? "true" : "false") + " num-buffers=" + std::to_string(frames) + " ";
    std::string tracker = "handtracker name=t particles=300 message-updates=none json-location=" + json;
    if (!head_uri.empty()) tracker += " head=" + head_uri + " steer=fixate";
    const std::string description = "handscenesrc eye=left" + common + "! t.sink_left handscenesrc eye=right" + common +
                                    "! t.sink_right " + tracker + " ! fakesink";
    TrackRun run;
    const auto start = std::chrono::steady_clock::now();
    run.bus = gc::test::run_pipeline(description);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.json = gc::test::read_lines(json);
    g_remove(json.c_str());
    return run;
}

TEST(HeadProperties, Defaults)
{
    gc::test::init_gstreamer();
    ElementPtr tracker(gst_element_factory_make("handtracker", nullptr));
    ElementPtr scene(gst_element_factory_make("handscenesrc", nullptr));
    ASSERT_TRUE(tracker && scene);
    gchar* head = nullptr;
    gdouble distance = 0.0;
    g_object_get(tracker.get(), "head", &head, "target-distance", &distance, nullptr);
    EXPECT_EQ(head, nullptr);
    EXPECT_DOUBLE_EQ(distance, 2000.0);
    int preset = 0;
    g_object_get(tracker.get(), "home-preset", &preset, nullptr);
    EXPECT_EQ(preset, -1);  // the head's own home position
    g_object_set(tracker.get(), "home-preset", 12, nullptr);
    g_object_get(tracker.get(), "home-preset", &preset, nullptr);
    EXPECT_EQ(preset, 12);
    gdouble widen = -1.0, home_after = -1.0;
    g_object_get(tracker.get(), "widen-after", &widen, "home-after", &home_after, nullptr);
    EXPECT_DOUBLE_EQ(widen, 0.0);  // never
    EXPECT_DOUBLE_EQ(home_after, 2.0);
    GParamSpec* spec = g_object_class_find_property(G_OBJECT_GET_CLASS(tracker.get()), "steer");
    ASSERT_TRUE(spec);
    GEnumClass* modes = G_ENUM_CLASS(g_type_class_ref(G_PARAM_SPEC_VALUE_TYPE(spec)));
    EXPECT_STREQ(g_enum_get_value(modes, G_PARAM_SPEC_ENUM(spec)->default_value)->value_nick, "fixate");
    gst_util_set_object_arg(G_OBJECT(tracker.get()), "steer", "point");
    int mode = -1;
    g_object_get(tracker.get(), "steer", &mode, nullptr);
    EXPECT_STREQ(g_enum_get_value(modes, mode)->value_nick, "point");
    g_type_class_unref(modes);
    g_object_get(scene.get(), "head", &head, nullptr);
    EXPECT_EQ(head, nullptr);
}

// The plane's coefficients as the property reads them back.
std::vector<double> target_plane(GstElement* tracker)
{
    GValue value = G_VALUE_INIT;
    g_value_init(&value, GST_TYPE_ARRAY);
    g_object_get_property(G_OBJECT(tracker), "target-plane", &value);
    std::vector<double> c;
    for (guint i = 0; i < gst_value_array_get_size(&value); ++i)
        c.push_back(g_value_get_double(gst_value_array_get_value(&value, i)));
    g_value_unset(&value);
    return c;
}

void count_warning(const gchar*, GLogLevelFlags, const gchar*, gpointer count) { ++*static_cast<int*>(count); }

// target-plane is unset by default, reads back with a unit normal, and a value that is no
// plane is refused with a warning and changes nothing.
TEST(HeadProperties, TargetPlaneReadsBackUnitAndRefusesWhatIsNoPlane)
{
    gc::test::init_gstreamer();
    ElementPtr tracker(gst_element_factory_make("handtracker", nullptr));
    ASSERT_TRUE(tracker);
    EXPECT_TRUE(target_plane(tracker.get()).empty());
    gst_util_set_object_arg(G_OBJECT(tracker.get()), "target-plane", "<0, 0, 2, -6000>");
    EXPECT_EQ(target_plane(tracker.get()), (std::vector<double>{0.0, 0.0, 1.0, -3000.0}));
    int warnings = 0;
    const guint handler = g_log_set_handler(nullptr, G_LOG_LEVEL_WARNING, count_warning, &warnings);
    for (const char* bad : {"<0, 0, 0, -3000>", "<0, 0, 1>", "<0, 0, 1, -3000, 7>"}) {
        gst_util_set_object_arg(G_OBJECT(tracker.get()), "target-plane", bad);
        EXPECT_EQ(target_plane(tracker.get()), (std::vector<double>{0.0, 0.0, 1.0, -3000.0})) << bad;
    }
    g_log_remove_handler(nullptr, handler);
    EXPECT_EQ(warnings, 3);
    gst_util_set_object_arg(G_OBJECT(tracker.get()), "target-plane", "<>");
    EXPECT_TRUE(target_plane(tracker.get()).empty());
}

TEST(HeadProperties, ABadUriFailsTheStartAndSaysWhy)
{
    gc::test::init_gstreamer();
    for (const char* element : {"handtracker", "handscenesrc"}) {
        const std::string pipeline = std::string(element) == "handtracker"
                                         ? "handscenesrc num-buffers=3 ! handtracker head=ftp://127.0.0.1:21 ! fakesink"
                                         : "handscenesrc num-buffers=3 head=tcp://127.0.0.1:notaport ! fakesink";
        const gc::test::RunResult r = gc::test::run_pipeline(pipeline, 10 * GST_SECOND);
        EXPECT_FALSE(r.eos) << element;
        EXPECT_NE(r.error.find("Invalid head URI"), std::string::npos) << element << ": " << r.error;
    }
}

TEST(HeadProperties, ABadDirectorUriFailsTheStartAndSaysWhy)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r = gc::test::run_pipeline(
        "handscenesrc num-buffers=3 ! handtracker director=visca-udp://127.0.0.1?zoom_max=lots ! fakesink",
        10 * GST_SECOND);
    EXPECT_FALSE(r.eos);
    EXPECT_NE(r.error.find("Invalid director URI"), std::string::npos) << r.error;
}

TEST(HeadProperties, HeadsThatDoNotAnswerChangeNothing)
{
    gc::test::init_gstreamer();
    const TrackRun reference = track("");
    ASSERT_TRUE(reference.bus.eos) << reference.bus.error;
    ASSERT_EQ(reference.json.size(), size_t(kFrames));

    gc::test::MisbehavingHead silent(gc::test::MisbehavingHead::Kind::Silent);
    gc::test::MisbehavingHead garbage(gc::test::MisbehavingHead::Kind::Garbage);
    const struct {
        const char* what;
        std::string uri;
    } heads[] = {
        {"nothing listening", "tcp://127.0.0.1:" + std::to_string(gc::test::closed_port())},
        {"accepts, never answers", silent.uri()},
        {"answers garbage", garbage.uri()},
    };
    std::printf("no head: %.1f ms per frame (whole pipeline)\n", 1000.0 * reference.seconds / kFrames);
    for (const auto& head : heads) {
        const TrackRun run = track(head.uri);
        std::printf("%s: %.1f ms per frame, %zu warning(s)\n", head.what, 1000.0 * run.seconds / kFrames,
                    run.bus.warnings.size());
        EXPECT_TRUE(run.bus.eos) << head.what << ": " << run.bus.error;
        // Without a pose the tracker sees exactly what it sees without a head.
        EXPECT_EQ(run.json, reference.json) << head.what;
        // A failure may come after these few frames are done; at most one warning.
        EXPECT_LE(run.bus.warnings.size(), 1u) << head.what;
    }
    EXPECT_GE(silent.accepted(), 1);
    EXPECT_GE(garbage.accepted(), 1);
}

TEST(HeadProperties, AnOutageIsReportedOnceNamingTheHead)
{
    // 3 s of live frames: the client gives up on the silent head after its 1 s timeout and
    // then retries every 0.5 s; the bus gets one warning for all of it, from handtracker.
    gc::test::init_gstreamer();
    gc::test::MisbehavingHead silent(gc::test::MisbehavingHead::Kind::Silent);
    const TrackRun run = track(silent.uri(), 90, true);
    EXPECT_TRUE(run.bus.eos) << run.bus.error;
    // Live: a slow machine (or a sanitizer build) may skip late pairs, but tracking goes on.
    EXPECT_GT(run.json.size(), 10u);
    std::vector<std::string> outage;
    for (const std::string& w : run.bus.warnings) {
        if (w.find(silent.uri()) != std::string::npos)
            outage.push_back(w);
        else  // a slow build is also told once that its views come too late to steer from
            EXPECT_NE(w.find("after capture"), std::string::npos) << w;
    }
    ASSERT_EQ(outage.size(), 1u);
    EXPECT_EQ(outage[0].rfind("t: ", 0), 0u) << outage[0];
    EXPECT_GE(silent.accepted(), 2);  // it kept trying
    const auto changes = run.bus.named("head-connection", "t");
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_STREQ(gst_structure_get_string(changes[0], "state"), "disconnected");
}

GstPadProbeReturn record_pts(GstPad*, GstPadProbeInfo* info, gpointer data)
{
    static_cast<std::vector<GstClockTime>*>(data)->push_back(GST_BUFFER_PTS(GST_PAD_PROBE_INFO_BUFFER(info)));
    return GST_PAD_PROBE_OK;
}

// A live handscenesrc reads the head's pose at each frame's capture time; downstream must see
// that same time as the frame's timestamp, or a tracker reading the pose at the timestamp it
// gets sees another pose than the one rendered (and steering on that difference runs away).
// The source starts late on purpose (a slow head connection or a loaded machine do that).
TEST(HeadProperties, ALiveFrameIsStampedWithTheTimeItsPoseWasReadAt)
{
    gc::test::init_gstreamer();
    gc::test::ElementPtr pipeline =
        gc::test::parse_pipeline("handscenesrc name=l is-live=true num-buffers=6 ! video/x-raw,width=320,height=240 ! "
                                 "fakesink name=k async=false");
    ASSERT_TRUE(pipeline);
    std::vector<GstClockTime> seen;
    gc::test::probe_buffers(pipeline.get(), "k", "sink", record_pts, &seen);
    // PLAYING, but the source's first frame only after 300 ms of running time.
    GstElement* source = gst_bin_get_by_name(GST_BIN(pipeline.get()), "l");
    gst_element_set_locked_state(source, TRUE);
    gst_element_set_state(pipeline.get(), GST_STATE_PLAYING);
    g_usleep(300000);
    gst_element_set_locked_state(source, FALSE);
    gst_element_sync_state_with_parent(source);
    gst_object_unref(source);
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 20 * GST_SECOND);
    ASSERT_TRUE(r.eos) << r.error;
    const auto truths = r.named("hand-truth", "l");
    ASSERT_EQ(truths.size(), 6u);
    ASSERT_EQ(seen.size(), 6u);
    for (size_t i = 0; i < seen.size(); ++i) {
        guint64 stamped = 0;
        ASSERT_TRUE(gst_structure_get_uint64(truths[i], "timestamp", &stamped));
        EXPECT_EQ(seen[i], stamped) << "frame " << i;
    }
    EXPECT_GE(seen[0], 250 * GST_MSECOND);  // the running time the first frame was taken at
}

}  // namespace
