// handtracker's json-location file: each frame's line is in the file, whole, when the frame
// leaves the element; the process killed part-way leaves only whole lines; a write that fails
// stops the pipeline with an error naming the file.
#include "gst_fixture.hpp"

#include "../core/line_watch.hpp"

#include <glib/gstdio.h>

#include <algorithm>
#include <string>
#include <vector>

namespace {

std::string temp_path(const char* name)
{
    return std::string(g_get_tmp_dir()) + "/gesturecam-json-" + std::to_string(::getpid()) + "-" + name;
}

// What the file held when each output buffer reached the sink.
struct Seen {
    std::string path;
    std::vector<std::string> contents;
};

GstPadProbeReturn record_file(GstPad*, GstPadProbeInfo*, gpointer data)
{
    Seen* seen = static_cast<Seen*>(data);
    seen->contents.push_back(gc::test::file_text(seen->path));
    return GST_PAD_PROBE_OK;
}

bool is_json_object_line(const std::string& line) { return line.rfind("{\"frame\":", 0) == 0 && line.back() == '}'; }

TEST(JsonLocation, EachLineIsInTheFileWhenItsFrameLeaves)
{
    gc::test::init_gstreamer();
    Seen seen{temp_path("live.jsonl"), {}};
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "handscenesrc eye=left num-buffers=8 ! t.sink_left handtracker name=t particles=200 message-updates=none "
        "json-location=" +
        seen.path + " ! fakesink name=sink");
    ASSERT_TRUE(pipeline);
    gc::test::probe_buffers(pipeline.get(), "sink", "sink", record_file, &seen);
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 30 * GST_SECOND);
    EXPECT_TRUE(r.eos) << r.error;
    ASSERT_EQ(seen.contents.size(), 8u);
    for (size_t i = 0; i < seen.contents.size(); ++i) {
        const std::string& text = seen.contents[i];
        EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), long(i + 1)) << "at output buffer " << i;
        EXPECT_TRUE(!text.empty() && text.back() == '\n') << "at output buffer " << i;
    }
    g_remove(seen.path.c_str());
}

TEST(JsonLocation, TerminatedPartWayLeavesWholeLines)
{
    const std::string path = temp_path("terminated.jsonl");
    const gc::test::LineWatch w = gc::test::watch_lines(
        {"gst-launch-1.0", "-q", "handscenesrc", "eye=left", "num-buffers=600", "!", "t.sink_left", "handtracker",
         "name=t", "particles=2000", "message-updates=none", "json-location=" + path, "!", "fakesink"},
        path, 8, std::chrono::seconds(60));
    ASSERT_TRUE(w.started);
    EXPECT_TRUE(w.terminated) << "the pipeline ended before the SIGTERM";
    EXPECT_TRUE(w.partial.empty()) << "a reader following the file saw part of a line, ending '"
                                   << w.partial.substr(w.partial.size() - std::min<size_t>(w.partial.size(), 40))
                                   << "'";
    ASSERT_FALSE(w.final_content.empty());
    EXPECT_EQ(w.final_content.back(), '\n');
    for (const std::string& line : gc::test::read_lines(path)) EXPECT_TRUE(is_json_object_line(line)) << line;
    g_remove(path.c_str());
}

TEST(JsonLocation, AFailedWriteStopsThePipelineNamingTheFile)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r = gc::test::run_pipeline(
        "videotestsrc num-buffers=3 ! t.sink_left handtracker name=t particles=100 json-location=/dev/full ! fakesink",
        20 * GST_SECOND);
    EXPECT_FALSE(r.eos);
    EXPECT_NE(r.error.find("/dev/full"), std::string::npos) << r.error;
}

}  // namespace
