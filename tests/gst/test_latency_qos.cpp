// Latency and QoS as a live pipeline meets them: the sources and the tracker report a latency
// the pipeline can be built with (no "please add queues"), the tracker's own processing time is
// in it, and output frames dropped under QoS are counted (JSON lines, stats, messages).
#include "gst_fixture.hpp"

#include <glib/gstdio.h>

#include <regex>

namespace {

using gc::test::ElementPtr;
using gc::test::StructurePtr;

const std::string kLiveEyes =
    "handscenesrc eye=left is-live=true truth-messages=false num-buffers=45 ! video/x-raw,width=320,height=240 ! "
    "t.sink_left handscenesrc eye=right is-live=true truth-messages=false num-buffers=45 ! "
    "video/x-raw,width=320,height=240 ! t.sink_right ";

StructurePtr stats_of(GstElement* pipeline)
{
    ElementPtr tracker(gst_bin_get_by_name(GST_BIN(pipeline), "t"));
    GstStructure* stats = nullptr;
    g_object_get(tracker.get(), "stats", &stats, nullptr);
    return StructurePtr(stats);
}

guint64 uint64_field(const GstStructure* s, const char* name)
{
    guint64 v = 0;
    EXPECT_TRUE(gst_structure_get_uint64(s, name, &v)) << name;
    return v;
}

// An encoder after the tracker adds latency of its own: with the sources' maximum latency equal
// to their minimum the sink warns that the pipeline is invalid and cannot keep the latency.
TEST(Latency, LiveStereoThroughAnEncoderNeedsNoQueues)
{
    gc::test::init_gstreamer();
    const auto result =
        gc::test::run_pipeline(kLiveEyes + "handtracker name=t message-updates=none ! videoconvert ! "
                                           "x264enc tune=zerolatency speed-preset=ultrafast ! fakesink sync=true");
    EXPECT_TRUE(result.eos) << result.error;
    for (const auto& warning : result.warnings)
        EXPECT_EQ(warning.find("please add queues"), std::string::npos) << warning;
}

// The latency handtracker reports downstream holds the time it takes on a frame.
TEST(Latency, TrackerReportsItsProcessingTime)
{
    gc::test::init_gstreamer();
    ElementPtr pipeline = gc::test::parse_pipeline(kLiveEyes + "handtracker name=t message-updates=none ! "
                                                               "fakesink name=sink sync=true");
    ASSERT_TRUE(pipeline);
    StructurePtr stats;
    GstClockTime min_latency = 0;
    const auto result = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND, [&] {
        stats = stats_of(pipeline.get());
        ElementPtr tracker(gst_bin_get_by_name(GST_BIN(pipeline.get()), "t"));
        GstQuery* query = gst_query_new_latency();
        GstPad* src = gst_element_get_static_pad(tracker.get(), "src");
        if (gst_pad_query(src, query)) gst_query_parse_latency(query, nullptr, &min_latency, nullptr);
        gst_object_unref(src);
        gst_query_unref(query);
    });
    EXPECT_TRUE(result.eos) << result.error;
    ASSERT_TRUE(stats);
    const guint64 processing = uint64_field(stats.get(), "processing-time-max");
    const guint64 reported = uint64_field(stats.get(), "latency");
    EXPECT_GT(processing, 0u);
    EXPECT_GE(reported + GST_MSECOND, processing);  // within a millisecond (rounded up)
    // One frame of the live source (1/30 s) plus the tracker's time.
    EXPECT_GE(min_latency, GST_SECOND / 30 + reported);
}

// A sink that finds frames late sends QoS upstream and GstVideoAggregator drops output frames:
// every input pair is either a JSON line or counted as skipped.
TEST(Qos, SkippedFramesAreCounted)
{
    gc::test::init_gstreamer();
    const int frames = 60;
    gchar* dir = g_dir_make_tmp("gesturecam-qos-XXXXXX", nullptr);
    ASSERT_NE(dir, nullptr);
    const std::string json = std::string(dir) + "/track.jsonl";
    const std::string eyes = " scene=light truth-messages=false num-buffers=" + std::to_string(frames) +
                             " ! video/x-raw,width=320,height=240 ! ";
    // identity sleeps 60 ms per frame: at 30 frames/s every frame reaches the sink late.
    ElementPtr pipeline =
        gc::test::parse_pipeline("handscenesrc eye=left" + eyes + "t.sink_left handscenesrc eye=right" + eyes +
                                 "t.sink_right handtracker name=t message-updates=every-frame json-location=" + json +
                                 " ! identity sleep-time=60000 ! fakesink sync=true qos=true");
    ASSERT_TRUE(pipeline);
    StructurePtr stats;
    const auto result =
        gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND, [&] { stats = stats_of(pipeline.get()); });
    EXPECT_TRUE(result.eos) << result.error;
    ASSERT_TRUE(stats);
    const guint64 skipped = uint64_field(stats.get(), "skipped-qos");
    const auto lines = gc::test::read_lines(json);
    EXPECT_GT(skipped, 0u);
    EXPECT_EQ(lines.size() + skipped, size_t(frames));
    EXPECT_EQ(uint64_field(stats.get(), "tracked"), lines.size());
    // The lines name the skips before them (those after the last line are only in the stats).
    static const std::regex field(R"("skipped_qos":([0-9]+))");
    guint64 named = 0;
    for (const auto& line : lines) {
        std::smatch m;
        if (std::regex_search(line, m, field)) named += std::stoull(m[1]);
    }
    EXPECT_GT(named, 0u);
    EXPECT_LE(named, skipped);
    // And the hand-pointing messages carry the count so far.
    const auto messages = result.named("hand-pointing");
    ASSERT_FALSE(messages.empty());
    EXPECT_LE(uint64_field(messages.back(), "skipped-qos"), skipped);
    EXPECT_GT(uint64_field(messages.back(), "skipped-qos"), 0u);
    g_remove(json.c_str());
    g_rmdir(dir);
    g_free(dir);
}

}  // namespace
