// File-based pipeline: a stereo sequence recorded with handscenesrc to PNG files is tracked
// back by gesturecam-track and by a multifilesrc -> handtracker pipeline. Both run the one
// PointingTracker code path, so they must write the same JSON lines; so must they on the real
// MP4 pair, which both decode through GStreamer. pipelines/files.sh refuses a picture over the
// frame limit from its header.
#include <gst/gst.h>
#include <gtest/gtest.h>

#include <glib/gstdio.h>
#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

constexpr int kFrames = 60;

std::string env(const char* name)
{
    const char* v = g_getenv(name);
    return v ? v : "";
}

// Runs a gst-launch style description to EOS; returns the error message, empty on success.
std::string play(const std::string& description)
{
    GError* error = nullptr;
    GstElement* pipeline = gst_parse_launch(description.c_str(), &error);
    if (error) {
        std::string message = error->message;
        g_error_free(error);
        if (pipeline) gst_object_unref(pipeline);
        return message;
    }
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
    GstBus* bus = gst_element_get_bus(pipeline);
    GstMessage* msg =
        gst_bus_timed_pop_filtered(bus, 120 * GST_SECOND, GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
    std::string result = msg ? "" : "timeout";
    if (msg && GST_MESSAGE_TYPE(msg) == GST_MESSAGE_ERROR) {
        GError* err = nullptr;
        gst_message_parse_error(msg, &err, nullptr);
        result = err->message;
        g_error_free(err);
    }
    if (msg) gst_message_unref(msg);
    gst_object_unref(bus);
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(pipeline);
    return result;
}

// The lines of a file.
std::vector<std::string> read_lines(const std::string& path)
{
    std::vector<std::string> lines;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// JSON lines with the pts_ns values blanked: the tool derives them from --fps, the element
// from the stream's timestamps, and the two may round the last nanosecond differently.
std::vector<std::string> tracking_lines(const std::string& path)
{
    static const std::regex pts(R"("pts_ns":(-?[0-9]+|null))");
    std::vector<std::string> lines = read_lines(path);
    for (std::string& line : lines) line = std::regex_replace(line, pts, "\"pts_ns\":_");
    return lines;
}

// The element's lines must be the tool's, frame by frame. The comparison means something only
// if the tracker did some tracking.
void expect_same_lines(const std::vector<std::string>& tool, const std::vector<std::string>& element, int frames)
{
    ASSERT_EQ(tool.size(), size_t(frames));
    ASSERT_EQ(element.size(), tool.size());
    int tracking = 0;
    for (size_t i = 0; i < tool.size(); ++i) {
        ASSERT_EQ(element[i], tool[i]) << "frame " << i;
        tracking += element[i].find("\"state\":\"tracking\"") != std::string::npos;
    }
    EXPECT_GT(tracking, 0);
}

// Runs gesturecam-track with `args`; a failure to start it or a non-zero exit fails the test.
void run_tool(const std::string& tool, const std::vector<std::string>& args)
{
    std::vector<gchar*> argv{const_cast<gchar*>(tool.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<gchar*>(a.c_str()));
    argv.push_back(nullptr);
    gint status = -1;
    gchar* err = nullptr;
    GError* spawn_error = nullptr;
    ASSERT_TRUE(g_spawn_sync(nullptr, argv.data(), nullptr, G_SPAWN_STDOUT_TO_DEV_NULL, nullptr, nullptr, nullptr, &err,
                             &status, &spawn_error))
        << (spawn_error ? spawn_error->message : "");
    EXPECT_TRUE(g_spawn_check_wait_status(status, nullptr)) << err;
    g_free(err);
}

TEST(FilePipeline, ToolAndElementWriteTheSameJson)
{
    gst_init(nullptr, nullptr);
    const std::string tool = env("GESTURECAM_TRACK_EXE");
    ASSERT_FALSE(tool.empty()) << "GESTURECAM_TRACK_EXE is not set";
    const std::string dir = env("GESTURECAM_BUILD_ROOT") + "/tests/pipeline/file_pipeline";
    for (const char* sub : {"", "/left", "/right"}) ASSERT_EQ(g_mkdir_with_parents((dir + sub).c_str(), 0755), 0);

    // Record: the scene's two views as PNG sequences (RGB straight from the source).
    const std::string scene =
        " scene=light motion=mixed seed=5 truth-messages=false num-buffers=" + std::to_string(kFrames) + " ";
    std::string error = play("handscenesrc eye=left" + scene +
                             "! video/x-raw,format=RGB ! pngenc ! "
                             "multifilesink location=" +
                             dir +
                             "/left/%05d.png "
                             "handscenesrc eye=right" +
                             scene +
                             "! video/x-raw,format=RGB ! pngenc ! "
                             "multifilesink location=" +
                             dir + "/right/%05d.png");
    ASSERT_EQ(error, "");

    // Track with the tool.
    const std::string tool_out = dir + "/tool.jsonl";
    const std::string left = dir + "/left/%05d.png";
    const std::string right = dir + "/right/%05d.png";
    run_tool(tool, {"--left", left, "--right", right, "--fps", "30", "--out", tool_out});

    // Track with the element, reading the same files (pngdec gives RGB: no videoconvert).
    const std::string element_out = dir + "/element.jsonl";
    error = play("multifilesrc location=" + left +
                 " caps=image/png,framerate=30/1 ! pngdec ! t.sink_left "
                 "multifilesrc location=" +
                 right +
                 " caps=image/png,framerate=30/1 ! pngdec ! t.sink_right "
                 "handtracker name=t message-updates=none json-location=" +
                 element_out + " ! fakesink sync=false");
    ASSERT_EQ(error, "");

    expect_same_lines(tracking_lines(tool_out), tracking_lines(element_out), kFrames);
}

// The real MP4 pair (H.264, 4:2:0), its first frames, tracked by the tool and by the pipeline
// pipelines/files.sh builds for video files: the tool must decode and convert the frames as
// the element receives them, and take the times from the stream as the element does.
TEST(FilePipeline, ToolAndElementWriteTheSameJsonOnTheRealMp4Pair)
{
    constexpr int kMp4Frames = 40;
    gst_init(nullptr, nullptr);
    const std::string tool = env("GESTURECAM_TRACK_EXE");
    ASSERT_FALSE(tool.empty()) << "GESTURECAM_TRACK_EXE is not set";
    const std::string data = env("GESTURECAM_SOURCE_ROOT") + "/tests/data/handpose3d/handpose3d_";
    const std::string left = data + "cam0.mp4", right = data + "cam1.mp4", calibration = data + "calib.yml";
    const std::string dir = env("GESTURECAM_BUILD_ROOT") + "/tests/pipeline/file_pipeline_mp4";
    ASSERT_EQ(g_mkdir_with_parents(dir.c_str(), 0755), 0);

    const std::string tool_out = dir + "/tool.jsonl";
    run_tool(tool, {"--left", left, "--right", right, "--calibration", calibration, "--max-frames",
                    std::to_string(kMp4Frames), "--out", tool_out});

    const std::string element_out = dir + "/element.jsonl";
    const std::string error =
        play("filesrc location=" + left + " ! decodebin ! videoconvert ! t.sink_left " + "filesrc location=" + right +
             " ! decodebin ! videoconvert ! t.sink_right " +
             "handtracker name=t message-updates=none calibration=" + calibration + " json-location=" + element_out +
             " ! identity eos-after=" + std::to_string(kMp4Frames) + " ! fakesink sync=false");
    ASSERT_EQ(error, "");

    // Times included: both take them from the stream.
    expect_same_lines(read_lines(tool_out), read_lines(element_out), kMp4Frames);
}

// A PNG that is only its signature and a header declaring width x height (RGB, 8 bits).
void write_png_header(const std::string& path, std::uint32_t width, std::uint32_t height)
{
    auto be32 = [](std::string& out, std::uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((v >> shift) & 0xFF));
    };
    std::string ihdr = "IHDR";
    be32(ihdr, width);
    be32(ihdr, height);
    ihdr += std::string("\x08\x02\x00\x00\x00", 5);
    std::string file = "\x89PNG\r\n\x1a\n";
    be32(file, 13);
    file += ihdr;
    be32(file, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(ihdr.data()), uInt(ihdr.size()))));
    std::ofstream(path, std::ios::binary) << file;
}

// A sequence whose third picture declares 30000 x 30000 pixels: pipelines/files.sh stops
// with an error naming that size and the limit (before, pngdec dropped it, or with real
// pixel data decoded all 2.7 GB of it first).
TEST(FilePipeline, FilesScriptRefusesAPictureOverTheLimitByItsHeader)
{
    gst_init(nullptr, nullptr);
    const std::string dir = env("GESTURECAM_BUILD_ROOT") + "/tests/pipeline/oversized";
    ASSERT_EQ(g_mkdir_with_parents((dir + "/seq").c_str(), 0755), 0);
    ASSERT_EQ(play("videotestsrc num-buffers=4 ! video/x-raw,width=64,height=48,format=RGB ! pngenc ! "
                   "multifilesink location=" +
                   dir + "/seq/%05d.png"),
              "");
    write_png_header(dir + "/seq/00002.png", 30000, 30000);

    const std::string script = env("GESTURECAM_SOURCE_ROOT") + "/pipelines/files.sh";
    const std::string pattern = dir + "/seq/%05d.png";
    const std::string out = dir + "/out";
    gchar* argv[] = {const_cast<gchar*>(script.c_str()), const_cast<gchar*>(pattern.c_str()),
                     const_cast<gchar*>(pattern.c_str()), const_cast<gchar*>(out.c_str()), nullptr};
    gint status = -1;
    gchar* output = nullptr;
    gchar* errors = nullptr;
    GError* spawn_error = nullptr;
    ASSERT_TRUE(g_spawn_sync(nullptr, argv, nullptr, G_SPAWN_DEFAULT, nullptr, nullptr, &output, &errors, &status,
                             &spawn_error))
        << (spawn_error ? spawn_error->message : "");
    const std::string said = std::string(output ? output : "") + (errors ? errors : "");
    g_free(output);
    g_free(errors);
    EXPECT_FALSE(g_spawn_check_wait_status(status, nullptr)) << said;
    EXPECT_NE(said.find("30000 x 30000 pixels is over the frame limit of 8192"), std::string::npos) << said;
}

}  // namespace
