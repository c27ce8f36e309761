// What GST_DEBUG=handtracker:7,gesturecam-head:7 shows: the hand's acquisition and gesture
// changes (INFO), every frame's details (DEBUG, LOG), and the head link's connection,
// disconnection and commands.
#include "gst_fixture.hpp"
#include "fake_heads.hpp"

#include "running_head.hpp"

#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace {

struct LogLine {
    std::string category;
    GstDebugLevel level;
    std::string text;
};

std::mutex log_mutex;
std::vector<LogLine> log_lines;

void collect(GstDebugCategory* category, GstDebugLevel level, const gchar*, const gchar*, gint, GObject*,
             GstDebugMessage* message, gpointer)
{
    const char* name = gst_debug_category_get_name(category);
    if (std::strcmp(name, "handtracker") != 0 && std::strcmp(name, "gesturecam-head") != 0) return;
    std::lock_guard lock(log_mutex);
    log_lines.push_back({name, level, gst_debug_message_get(message)});
}

class DebugLog : public ::testing::Test {
protected:
    void SetUp() override
    {
        gc::test::init_gstreamer();
        gst_debug_set_active(TRUE);
        gst_debug_remove_log_function(gst_debug_log_default);
        gst_debug_add_log_function(collect, nullptr, nullptr);
        gst_debug_set_threshold_from_string("handtracker:7,gesturecam-head:7", TRUE);
        std::lock_guard lock(log_mutex);
        log_lines.clear();
    }
    void TearDown() override
    {
        gst_debug_set_threshold_from_string("", TRUE);
        gst_debug_remove_log_function(collect);
    }

    // The lines of `category` at `level` that contain `text`.
    static int count(const char* category, GstDebugLevel level, const std::string& text)
    {
        std::lock_guard lock(log_mutex);
        int n = 0;
        for (const auto& line : log_lines)
            n += line.category == category && line.level == level && line.text.find(text) != std::string::npos;
        return n;
    }
};

TEST_F(DebugLog, TrackerLogsTheHandAndEveryFrame)
{
    const int frames = 60;
    const std::string eye =
        " scene=light motion=translate seed=3 truth-messages=false num-buffers=" + std::to_string(frames) + " ! ";
    const auto result =
        gc::test::run_pipeline("handscenesrc eye=left" + eye + "t.sink_left handscenesrc eye=right" + eye +
                               "t.sink_right handtracker name=t message-updates=none ! "
                               "fakesink sync=false");
    ASSERT_TRUE(result.eos) << result.error;
    EXPECT_GE(count("handtracker", GST_LEVEL_INFO, "left view acquired the hand"), 1);
    EXPECT_GE(count("handtracker", GST_LEVEL_INFO, "left view gesture unknown -> "), 1);
    EXPECT_EQ(count("handtracker", GST_LEVEL_DEBUG, ": left view "), frames);
    EXPECT_EQ(count("handtracker", GST_LEVEL_DEBUG, ": right view "), frames);
    EXPECT_GE(count("handtracker", GST_LEVEL_DEBUG, "ray azimuth"), 1);
    EXPECT_EQ(count("handtracker", GST_LEVEL_LOG, " made in "), frames);
}

TEST_F(DebugLog, HeadLinkLogsConnectionAndCommands)
{
    gc::loopback::RunningHead head(gc::loopback::loopback_head(0, 0.02));
    const std::string eye =
        " is-live=true scene=light motion=translate seed=3 truth-messages=false head=" + head.uri() +
        " num-buffers=60 ! ";
    const auto result =
        gc::test::run_pipeline("handscenesrc eye=left" + eye + "t.sink_left handscenesrc eye=right" + eye +
                               "t.sink_right handtracker name=t particles=500 head=" + head.uri() +
                               " steer=fixate message-updates=none ! fakesink");
    ASSERT_TRUE(result.eos) << result.error;
    EXPECT_GE(
        count("gesturecam-head", GST_LEVEL_INFO, "head tcp://127.0.0.1:" + std::to_string(head.port()) + " connected"),
        1);
    EXPECT_GE(count("gesturecam-head", GST_LEVEL_DEBUG, "head command: "), 1);
}

TEST_F(DebugLog, HeadLinkLogsAHeadThatCannotBeReached)
{
    const std::string uri = "tcp://127.0.0.1:" + std::to_string(gc::test::closed_port());
    const auto result = gc::test::run_pipeline(
        "handscenesrc eye=left num-buffers=15 truth-messages=false ! t.sink_left handscenesrc eye=right "
        "num-buffers=15 truth-messages=false ! t.sink_right handtracker name=t particles=200 head=" +
        uri + " steer=off message-updates=none ! fakesink");
    ASSERT_TRUE(result.eos) << result.error;
    EXPECT_GE(count("gesturecam-head", GST_LEVEL_INFO, "head " + uri + " disconnected: "), 1);
}

}  // namespace
