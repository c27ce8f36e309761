// The head's token in handtracker: never shown where the element shows its head URI
// (warnings, errors, head-connection messages, the `head` property read back), and read
// from the file named by `head-token-file`, so a pipeline's properties can be read back
// and set again without losing it.
#include "fake_heads.hpp"
#include "gst_fixture.hpp"

#include "running_head.hpp"

#include <glib/gstdio.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

using gc::test::ElementPtr;

constexpr const char* kSecret = "Tr0ub4dor-and-3";

// What a run left on the bus, as text: every error, warning and info with its detail, and
// every element message; and the head-connection states handtracker posted.
struct BusText {
    std::string text;
    std::vector<std::string> connection_states;
    int warnings = 0;
    bool eos = false;
    bool failed = false;
};

BusText play(GstElement* pipeline, GstClockTime timeout = 20 * GST_SECOND)
{
    BusText r;
    GstBus* bus = gst_element_get_bus(pipeline);
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
    const GstClockTime deadline = gst_util_get_timestamp() + timeout;
    for (bool stop = false; !stop;) {
        const GstClockTime now = gst_util_get_timestamp();
        if (now >= deadline) break;
        GstMessage* msg = gst_bus_timed_pop(bus, deadline - now);
        if (!msg) continue;
        GError* err = nullptr;
        gchar* debug = nullptr;
        switch (GST_MESSAGE_TYPE(msg)) {
        case GST_MESSAGE_EOS:
            r.eos = stop = true;
            break;
        case GST_MESSAGE_ERROR:
            gst_message_parse_error(msg, &err, &debug);
            r.failed = stop = true;
            break;
        case GST_MESSAGE_WARNING:
            gst_message_parse_warning(msg, &err, &debug);
            ++r.warnings;
            break;
        case GST_MESSAGE_INFO:
            gst_message_parse_info(msg, &err, &debug);
            break;
        case GST_MESSAGE_ELEMENT: {
            const GstStructure* s = gst_message_get_structure(msg);
            gchar* text = gst_structure_to_string(s);
            r.text += std::string(text) + "\n";
            g_free(text);
            if (gst_structure_has_name(s, "head-connection"))
                r.connection_states.emplace_back(gst_structure_get_string(s, "state"));
            break;
        }
        default:
            break;
        }
        if (err) r.text += std::string(err->message) + "\n" + (debug ? debug : "") + "\n";
        g_clear_error(&err);
        g_free(debug);
        gst_message_unref(msg);
    }
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(bus);
    return r;
}

// Two live synthetic eyes into handtracker `t` (properties set by the caller) for 1 s.
ElementPtr tracker_pipeline()
{
    const std::string eye = " is-live=true scene=light seed=3 truth-messages=false num-buffers=30 ";
    return gc::test::parse_pipeline("handscenesrc eye=left" + eye + "! t.sink_left handscenesrc eye=right" + eye +
                                    "! t.sink_right handtracker name=t particles=100 message-updates=none steer=off "
                                    "! fakesink");
}

ElementPtr tracker_of(GstElement* pipeline) { return ElementPtr(gst_bin_get_by_name(GST_BIN(pipeline), "t")); }

// One live synthetic eye for 1 s; the caller sets handscenesrc's head properties.
ElementPtr scene_source_pipeline()
{
    return gc::test::parse_pipeline("handscenesrc name=s is-live=true truth-messages=false num-buffers=30 ! fakesink");
}

ElementPtr scene_source_of(GstElement* pipeline) { return ElementPtr(gst_bin_get_by_name(GST_BIN(pipeline), "s")); }

std::string string_property(GstElement* element, const char* name)
{
    gchar* value = nullptr;
    g_object_get(element, name, &value, nullptr);
    std::string out = value ? value : "";
    g_free(value);
    return out;
}

// A file holding the token, removed at the end of the scope.
struct TokenFile {
    explicit TokenFile(const std::string& token)
        : path(std::string(g_get_tmp_dir()) + "/gesturecam-token-" + std::to_string(getpid()))
    {
        std::FILE* f = std::fopen(path.c_str(), "w");
        std::fprintf(f, "%s\n", token.c_str());
        std::fclose(f);
    }
    ~TokenFile() { g_remove(path.c_str()); }
    std::string path;
};

gc::headctl::HeadServerConfig head_with_token()
{
    gc::headctl::HeadServerConfig config = gc::loopback::loopback_head();
    config.token = kSecret;
    return config;
}

TEST(HeadToken, IsHiddenInWarningsAndMessages)
{
    gc::test::init_gstreamer();
    const std::string uri = "tcp://127.0.0.1:" + std::to_string(gc::test::closed_port()) + "?token=" + kSecret;
    for (const bool tracker : {true, false}) {
        ElementPtr pipeline = tracker ? tracker_pipeline() : scene_source_pipeline();
        ASSERT_TRUE(pipeline);
        g_object_set((tracker ? tracker_of(pipeline.get()) : scene_source_of(pipeline.get())).get(), "head",
                     uri.c_str(), nullptr);
        const BusText run = play(pipeline.get());
        EXPECT_TRUE(run.eos);
        EXPECT_GE(run.warnings, 1);  // nothing listens there
        ASSERT_FALSE(run.connection_states.empty());
        EXPECT_EQ(run.text.find(kSecret), std::string::npos) << run.text;
        EXPECT_NE(run.text.find("token=***"), std::string::npos) << run.text;
    }
}

TEST(HeadToken, IsHiddenInTheErrorForAnInvalidUri)
{
    gc::test::init_gstreamer();
    for (const char* element : {"handtracker", "handscenesrc"}) {
        const std::string bad = std::string("tcp://127.0.0.1:notaport?token=") + kSecret;
        const std::string description = std::string(element) == "handtracker"
                                            ? "handscenesrc num-buffers=3 ! handtracker head=" + bad + " ! fakesink"
                                            : "handscenesrc num-buffers=3 head=" + bad + " ! fakesink";
        ElementPtr pipeline = gc::test::parse_pipeline(description);
        ASSERT_TRUE(pipeline);
        const BusText run = play(pipeline.get(), 10 * GST_SECOND);
        EXPECT_TRUE(run.failed) << element;
        EXPECT_NE(run.text.find("Invalid head URI"), std::string::npos) << run.text;
        EXPECT_EQ(run.text.find(kSecret), std::string::npos) << element << ": " << run.text;
    }
}

TEST(HeadToken, AFileAuthenticatesAndACopyOfThePropertiesStillDoes)
{
    gc::test::init_gstreamer();
    gc::loopback::RunningHead head(head_with_token());
    const TokenFile file(kSecret);

    ElementPtr first = tracker_pipeline();
    ASSERT_TRUE(first);
    g_object_set(tracker_of(first.get()).get(), "head", head.uri().c_str(), "head-token-file", file.path.c_str(),
                 nullptr);
    const BusText authenticated = play(first.get());
    EXPECT_TRUE(authenticated.eos);
    EXPECT_EQ(authenticated.connection_states, std::vector<std::string>{"connected"}) << authenticated.text;
    EXPECT_EQ(authenticated.warnings, 0) << authenticated.text;

    // Every property read from one element and set on another: the copy connects too.
    ElementPtr second = tracker_pipeline();
    ASSERT_TRUE(second);
    for (const char* name : {"head", "head-token-file"})
        g_object_set(tracker_of(second.get()).get(), name, string_property(tracker_of(first.get()).get(), name).c_str(),
                     nullptr);
    const BusText copied = play(second.get());
    EXPECT_EQ(copied.connection_states, std::vector<std::string>{"connected"}) << copied.text;

    // Without the file the head refuses the element.
    ElementPtr third = tracker_pipeline();
    ASSERT_TRUE(third);
    g_object_set(tracker_of(third.get()).get(), "head", head.uri().c_str(), nullptr);
    const BusText refused = play(third.get());
    EXPECT_GE(refused.warnings, 1);
    EXPECT_EQ(refused.connection_states, std::vector<std::string>{"disconnected"}) << refused.text;
}

// The director's token file authenticates it as head-token-file does the head; without it
// the director is refused (a warning), and the tracking goes on.
TEST(HeadToken, AFileAuthenticatesTheDirector)
{
    gc::test::init_gstreamer();
    gc::loopback::RunningHead director(head_with_token());
    const TokenFile file(kSecret);
    ElementPtr with_file = tracker_pipeline();
    ASSERT_TRUE(with_file);
    g_object_set(tracker_of(with_file.get()).get(), "director", director.uri().c_str(), "director-token-file",
                 file.path.c_str(), nullptr);
    EXPECT_EQ(string_property(tracker_of(with_file.get()).get(), "director-token-file"), file.path);
    const BusText authenticated = play(with_file.get());
    EXPECT_TRUE(authenticated.eos);
    EXPECT_EQ(authenticated.connection_states, std::vector<std::string>{"connected"}) << authenticated.text;
    EXPECT_EQ(authenticated.warnings, 0) << authenticated.text;

    ElementPtr without = tracker_pipeline();
    ASSERT_TRUE(without);
    g_object_set(tracker_of(without.get()).get(), "director", director.uri().c_str(), nullptr);
    const BusText refused = play(without.get());
    EXPECT_TRUE(refused.eos);
    EXPECT_GE(refused.warnings, 1);
    EXPECT_EQ(refused.connection_states, std::vector<std::string>{"disconnected"}) << refused.text;
}

// Sets `element`'s head to `uri` with the token, checks that it reads back hidden, and sets
// back what was read.
void set_head_with_token_and_read_back(GstElement* element, const std::string& uri)
{
    g_object_set(element, "head", (uri + "?token=" + kSecret).c_str(), nullptr);
    const std::string shown = string_property(element, "head");
    EXPECT_EQ(shown, uri + "?token=***");
    g_object_set(element, "head", shown.c_str(), nullptr);
}

// The `head` property reads back with the token hidden; setting what was read keeps it.
TEST(HeadToken, ATokenInTheUriIsHiddenWhenReadBackAndKeptWhenSetAgain)
{
    gc::test::init_gstreamer();
    gc::loopback::RunningHead head(head_with_token());
    ElementPtr pipeline = tracker_pipeline();
    ASSERT_TRUE(pipeline);
    set_head_with_token_and_read_back(tracker_of(pipeline.get()).get(), head.uri());
    const BusText run = play(pipeline.get());
    EXPECT_EQ(run.connection_states, std::vector<std::string>{"connected"}) << run.text;
}

// handscenesrc reads the same head: its `head` reads back without the token, setting back
// what was read keeps it, and a file authenticates it as it does handtracker.
TEST(HeadToken, TheSceneSourceHidesItAndReadsItFromAFile)
{
    gc::test::init_gstreamer();
    gc::loopback::RunningHead head(head_with_token());
    ElementPtr pipeline = scene_source_pipeline();
    ASSERT_TRUE(pipeline);
    set_head_with_token_and_read_back(scene_source_of(pipeline.get()).get(), head.uri());
    const BusText kept = play(pipeline.get());
    EXPECT_TRUE(kept.eos);
    EXPECT_EQ(kept.connection_states, std::vector<std::string>{"connected"}) << kept.text;

    const TokenFile file(kSecret);
    ElementPtr from_file = scene_source_pipeline();
    ASSERT_TRUE(from_file);
    g_object_set(scene_source_of(from_file.get()).get(), "head", head.uri().c_str(), "head-token-file",
                 file.path.c_str(), nullptr);
    const BusText authenticated = play(from_file.get());
    EXPECT_EQ(authenticated.connection_states, std::vector<std::string>{"connected"}) << authenticated.text;
    EXPECT_EQ(authenticated.warnings, 0) << authenticated.text;
    EXPECT_EQ(authenticated.text.find(kSecret), std::string::npos) << authenticated.text;

    ElementPtr unreadable = scene_source_pipeline();
    ASSERT_TRUE(unreadable);
    g_object_set(scene_source_of(unreadable.get()).get(), "head", head.uri().c_str(), "head-token-file",
                 "/nonexistent/head-token", nullptr);
    const BusText failed = play(unreadable.get(), 10 * GST_SECOND);
    EXPECT_TRUE(failed.failed);
    EXPECT_NE(failed.text.find("/nonexistent/head-token"), std::string::npos) << failed.text;
}

TEST(HeadToken, AnUnreadableTokenFileFailsTheStartAndIsNamed)
{
    gc::test::init_gstreamer();
    ElementPtr pipeline = tracker_pipeline();
    ASSERT_TRUE(pipeline);
    g_object_set(tracker_of(pipeline.get()).get(), "head", "tcp://127.0.0.1:5050", "head-token-file",
                 "/nonexistent/head-token", nullptr);
    const BusText run = play(pipeline.get(), 10 * GST_SECOND);
    EXPECT_TRUE(run.failed);
    EXPECT_NE(run.text.find("/nonexistent/head-token"), std::string::npos) << run.text;
}

}  // namespace
