// gesturecam-track end to end: a rendered stereo sequence written as PNG files goes in, JSON
// lines come out; wrong inputs and options give a non-zero status and a message naming them.
#include "line_watch.hpp"
#include "tool_run.hpp"
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "tools/json_reader.hpp"
#include "tools/tool_version.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using gc::tools::JsonReader;
using gc::tools::JsonValue;

namespace {

using gc_test::read_text;
using gc_test::RunResult;

std::vector<std::string> lines_of(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Fast PNG writing: the test's time goes to tracking, not to compression.
bool write_png(const std::filesystem::path& p, const cv::Mat& image)
{
    return cv::imwrite(p.string(), image, {cv::IMWRITE_PNG_COMPRESSION, 1});
}

void write_bytes(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

// Keeps the first `fraction` of a file, as a copy cut short would.
void truncate_file(const fs::path& p, double fraction)
{
    fs::resize_file(p, static_cast<std::uintmax_t>(static_cast<double>(fs::file_size(p)) * fraction));
}

std::string big_endian(std::uint32_t v, int bytes)
{
    std::string out;
    for (int i = bytes - 1; i >= 0; --i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
    return out;
}

// A PNG that declares a width x height RGB image and then holds nothing that decodes.
std::string png_claiming(std::uint32_t width, std::uint32_t height)
{
    return std::string("\x89PNG\r\n\x1a\n", 8) + big_endian(13, 4) + "IHDR" + big_endian(width, 4) +
           big_endian(height, 4) + std::string("\x08\x02\x00\x00\x00", 5) + big_endian(0, 4) + big_endian(64, 4) +
           "IDAT" + std::string(64, '\x5a');
}

// A JPEG (SOI, a JFIF segment, a baseline frame header) that declares width x height.
std::string jpeg_claiming(std::uint16_t width, std::uint16_t height)
{
    const std::string jfif =
        std::string("\xFF\xE0", 2) + big_endian(16, 2) + std::string("JFIF\0\x01\x01\0\0\x01\0\x01\0\0", 14);
    const std::string frame = std::string("\xFF\xC0", 2) + big_endian(17, 2) + "\x08" + big_endian(height, 2) +
                              big_endian(width, 2) + std::string("\x03\x01\x22\x00\x02\x11\x01\x03\x11\x01", 10);
    return std::string("\xFF\xD8", 2) + jfif + frame + std::string(64, '\x5a');
}

class TrackTool : public ::testing::Test {
protected:
    static constexpr int kFrames = 45;
    static constexpr int kFormatFrames = 20;
    static constexpr int kCorruptFrames = 12;  // frame 5 of them is a PNG cut short
    static constexpr int kVideoFrames = 24;

    static void SetUpTestSuite()
    {
        dir_ = fs::temp_directory_path() / ("gesturecam-track-test-" + std::to_string(::getpid()));
        fs::create_directories(dir_ / "left");
        fs::create_directories(dir_ / "right");
        fs::create_directories(dir_ / "short");
        fs::create_directories(dir_ / "small");
        fs::create_directories(dir_ / "bgra");
        fs::create_directories(dir_ / "grey16");
        fs::create_directories(dir_ / "corrupt");
        fs::create_directories(dir_ / "wide");
        cv::VideoWriter video((dir_ / "cut.avi").string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30.0,
                              cv::Size(640, 480));
        ASSERT_TRUE(video.isOpened());
        gc::sim::SceneConfig config;
        config.preset = gc::sim::Preset::Clean;
        config.motion = gc::sim::Motion::Translate;
        config.seed = 2;
        const gc::sim::Scene scene(config);
        cv::Mat frame, small;
        gc::sim::EyeTruth truth;
        truth_boxes_.clear();
        for (int f = 0; f < kFrames; ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "%03d.png", f);
            scene.render(f, gc::Eye::Left, {}, frame, &truth);
            truth_boxes_.push_back(truth.visible ? truth.bbox : cv::Rect());
            ASSERT_TRUE(write_png(dir_ / "left" / name, frame));
            if (f < kFormatFrames) {
                cv::Mat converted;
                cv::cvtColor(frame, converted, cv::COLOR_BGR2BGRA);
                ASSERT_TRUE(write_png(dir_ / "bgra" / name, converted));
                cv::cvtColor(frame, converted, cv::COLOR_BGR2GRAY);
                converted.convertTo(converted, CV_16U, 257.0);
                ASSERT_TRUE(write_png(dir_ / "grey16" / name, converted));
            }
            if (f < 3) {
                cv::resize(frame, small, cv::Size(320, 240));
                ASSERT_TRUE(write_png(dir_ / "small" / name, small));
            }
            if (f < kCorruptFrames) {
                ASSERT_TRUE(write_png(dir_ / "corrupt" / name, frame));
            }
            if (f < kVideoFrames) video.write(frame);
            scene.render(f, gc::Eye::Right, {}, frame);
            ASSERT_TRUE(write_png(dir_ / "right" / name, frame));
            if (f < 5) {
                ASSERT_TRUE(write_png(dir_ / "short" / name, frame));
            }
        }
        video.release();
        truncate_file(dir_ / "cut.avi", 0.5);
        truncate_file(dir_ / "corrupt" / "005.png", 0.3);
        // One pixel wider than the limit: a real image that decodes.
        cv::Mat wide(40, 8193, CV_8UC3, cv::Scalar(90, 120, 160));
        ASSERT_TRUE(write_png(dir_ / "wide" / "000.png", wide));
        write_bytes(dir_ / "claims.png", png_claiming(30000, 30000));
        write_bytes(dir_ / "claims.jpg", jpeg_claiming(30000, 20000));
    }

    static void TearDownTestSuite()
    {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    static std::string pattern(const char* folder) { return (dir_ / folder / "%03d.png").string(); }

    // Runs the tool with `args` (already shell-quoted where needed); its standard output goes
    // to `stdout_path` when given, else it is captured.
    static RunResult run(const std::string& args, const std::string& stdout_path = "")
    {
        const char* exe = std::getenv("GESTURECAM_GESTURECAM_TRACK_EXE");
        if (exe == nullptr) {
            ADD_FAILURE() << "GESTURECAM_GESTURECAM_TRACK_EXE is not set";
            return {};
        }
        const fs::path out = dir_ / "stdout.txt";
        const fs::path err = dir_ / "stderr.txt";
        const std::string cmd = quoted(exe) + " " + args + " > " +
                                quoted(stdout_path.empty() ? out.string() : stdout_path) + " 2> " +
                                quoted(err.string());
        const int raw = std::system(cmd.c_str());
        RunResult r;
        r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        r.out = stdout_path.empty() ? read_text(out) : "";
        r.err = read_text(err);
        return r;
    }

    // The "frame" values of JSON lines.
    static std::vector<int> frame_numbers(const std::string& text)
    {
        std::vector<int> frames;
        for (const std::string& line : lines_of(text))
            frames.push_back(static_cast<int>(JsonReader::parse(line)["frame"].number()));
        return frames;
    }

    static inline fs::path dir_;
    static inline std::vector<cv::Rect> truth_boxes_;
};

TEST_F(TrackTool, StereoWritesOneValidLinePerFrameAndTracks)
{
    const fs::path out = dir_ / "stereo.jsonl";
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("right")) +
                            " --particles 300 --seed 3 --fps 30 --out " + quoted(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.out.empty()) << "with --out nothing goes to stdout";
    const std::vector<std::string> lines = lines_of(read_text(out));
    ASSERT_EQ(lines.size(), static_cast<std::size_t>(kFrames));
    int first_tracking = -1, overlapping = 0, tracking = 0;
    for (int i = 0; i < kFrames; ++i) {
        JsonValue v;
        ASSERT_NO_THROW(v = JsonReader::parse(lines[i])) << "line " << i << ": " << lines[i];
        for (const char* key : {"frame", "pts_ns", "state", "left", "right", "pointing"})
            ASSERT_TRUE(v.has(key)) << key << " missing in line " << i;
        EXPECT_EQ(v["frame"].number(), i);
        EXPECT_NEAR(v["pts_ns"].number(), i * 1e9 / 30.0, 1.0);
        const std::string& state = v["state"].string();
        ASSERT_TRUE(state == "tracking" || state == "acquiring" || state == "lost") << state;
        if (state != "tracking") continue;
        first_tracking = first_tracking < 0 ? i : first_tracking;
        ++tracking;
        const JsonValue& b = v["left"]["bbox"];
        const cv::Rect box(int(b[0].number()), int(b[1].number()), int(b[2].number()), int(b[3].number()));
        overlapping += (box & truth_boxes_[i]).area() > 0 ? 1 : 0;
        EXPECT_TRUE(v["right"].is_object());
        EXPECT_GE(v["left"]["contour"].array().size(), 8u);
    }
    ASSERT_GE(first_tracking, 0) << "never tracked";
    EXPECT_LT(first_tracking, 30);
    EXPECT_GE(overlapping, tracking * 9 / 10);
}

TEST_F(TrackTool, MonoToStdoutHasNoRightAndNoPointing)
{
    const RunResult r = run("--left " + quoted(pattern("left")) + " --particles 100 --max-frames 12");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 12u);
    for (const std::string& line : lines) {
        const JsonValue v = JsonReader::parse(line);
        EXPECT_FALSE(v.has("right"));
        EXPECT_FALSE(v.has("pointing"));
        EXPECT_TRUE(v.has("left"));
        EXPECT_TRUE(v["pts_ns"].is_null()) << "an image sequence has no time without --fps";
    }
}

TEST_F(TrackTool, BgraAndSixteenBitGreyInputsAreConvertedToBgr)
{
    const std::string common = " --particles 100 --max-frames " + std::to_string(kFormatFrames);
    const RunResult bgr = run("--left " + quoted(pattern("left")) + common);
    const RunResult bgra = run("--left " + quoted(pattern("bgra")) + common);
    ASSERT_EQ(bgr.status, 0) << bgr.err;
    ASSERT_EQ(bgra.status, 0) << bgra.err;
    EXPECT_EQ(lines_of(bgra.out).size(), static_cast<std::size_t>(kFormatFrames));
    EXPECT_EQ(bgra.out, bgr.out) << "the alpha channel must not change the tracking";
    const RunResult grey = run("--left " + quoted(pattern("grey16")) + common);
    ASSERT_EQ(grey.status, 0) << grey.err;
    EXPECT_EQ(lines_of(grey.out).size(), static_cast<std::size_t>(kFormatFrames));
}

TEST_F(TrackTool, MissingInputsAreNamed)
{
    RunResult r = run("--left " + quoted((dir_ / "nothing.mp4").string()));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("nothing.mp4"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("no such file"), std::string::npos) << r.err;

    r = run("--left " + quoted(pattern("left")) + " --right " + quoted((dir_ / "none" / "%03d.png").string()));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("right input"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("pattern"), std::string::npos) << r.err;
}

TEST_F(TrackTool, MismatchedSizesAreAnError)
{
    const fs::path out = dir_ / "mismatch.jsonl";
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("small")) + " --out " +
                            quoted(out.string()));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("640x480"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("320x240"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "a rejected input must not leave an output file";
}

TEST_F(TrackTool, CalibrationForAnotherSizeIsAnError)
{
    const fs::path calib = dir_ / "small_rig.yml";
    gc::save_calibration(gc::default_calibration(cv::Size(320, 240)), calib.string());
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("right")) +
                            " --calibration " + quoted(calib.string()));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("640x480"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("320x240"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());

    // The same file for the right size is accepted.
    gc::save_calibration(gc::default_calibration(cv::Size(640, 480)), calib.string());
    const RunResult ok = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("right")) +
                             " --calibration " + quoted(calib.string()) + " --particles 50 --max-frames 3");
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_EQ(lines_of(ok.out).size(), 3u);
}

TEST_F(TrackTool, ShorterRightStopsWithAWarning)
{
    const RunResult r =
        run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("short")) + " --particles 50");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lines_of(r.out).size(), 5u);
    EXPECT_NE(r.err.find("right input ended at frame 5"), std::string::npos) << r.err;
}

TEST_F(TrackTool, BadCalibrationFileIsNamed)
{
    const fs::path calib = dir_ / "broken.yml";
    std::ofstream(calib) << "%YAML:1.0\n---\nimage_width: 640\n";
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("right")) +
                            " --calibration " + quoted(calib.string()));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("broken.yml"), std::string::npos) << r.err;
}

TEST_F(TrackTool, BadCommandLinesExitWithStatusTwo)
{
    const std::string left = " --left " + quoted(pattern("left"));
    const std::vector<std::pair<std::string, std::string>> cases{
        {left + " --particles 0", "--particles"},
        {left + " --particles 12abc", "--particles"},
        {left + " --fps -5", "--fps"},
        {left + " --tracking-width 10", "--tracking-width"},
        {left + " --seed", "--seed"},
        {left + " --frobnicate 1", "--frobnicate"},
        {"--particles 10", "--left"},
        {left + " stray", "stray"},
    };
    for (const auto& [args, named] : cases) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_NE(r.err.find(named), std::string::npos) << args << " -> " << r.err;
    }
    const RunResult help = run("--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("--left"), std::string::npos);
    EXPECT_EQ(run("-h").out, help.out);
}

TEST_F(TrackTool, BadOptionGetsAOneLineHint)
{
    for (const char* args : {"--left x --frobnicate", "--left x --particles 0", "--left x --skip-bad-frames=1"}) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
        EXPECT_NE(r.err.find("--help"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("usage:"), std::string::npos) << r.err;
    }
}

TEST_F(TrackTool, AnswersVersion)
{
    const RunResult r = run("--version");
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "gesturecam-track " + std::string(GC_TOOL_VERSION) + "\n");
}

TEST_F(TrackTool, ProgressLinesOnStderr)
{
    const std::string mono = "--left " + quoted(pattern("left")) + " --particles 50 --max-frames 6";
    // Every frame of this run takes longer than the interval asked for.
    const RunResult r = run(mono + " --progress 0.000001");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("gesturecam-track: 1 frames of 6, "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("gesturecam-track: 6 frames of 6, "), std::string::npos) << r.err;
    const RunResult quiet = run(mono + " --progress 0");
    ASSERT_EQ(quiet.status, 0) << quiet.err;
    EXPECT_EQ(quiet.err.find("frames/s"), std::string::npos) << quiet.err;
    EXPECT_EQ(quiet.out, r.out);
}

}  // namespace

namespace {

// A WAV file of one second of silence at 8 kHz, 16-bit mono: a stream, but not a video.
std::string silent_wav()
{
    auto le = [](std::uint32_t v, int bytes) {
        std::string out;
        for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
        return out;
    };
    const std::uint32_t data_bytes = 16000;
    return "RIFF" + le(36 + data_bytes, 4) + "WAVEfmt " + le(16, 4) + le(1, 2) + le(1, 2) + le(8000, 4) +
           le(16000, 4) + le(2, 2) + le(16, 2) + "data" + le(data_bytes, 4) + std::string(data_bytes, '\0');
}

// What GStreamer found wrong is part of the error: a file of no known type, a stream that is
// not video. Before, both said "cannot be decoded" and nothing more.
TEST_F(TrackTool, InputsThatAreNotVideoSayWhy)
{
    write_bytes(dir_ / "text.mp4", "this is not a video\n");
    write_bytes(dir_ / "silence.wav", silent_wav());
    const RunResult text = run("--left " + quoted((dir_ / "text.mp4").string()));
    EXPECT_EQ(text.status, 1) << text.err;
    EXPECT_NE(text.err.find("cannot be decoded (Could not determine type of stream.)"), std::string::npos)
        << text.err;
    const RunResult audio = run("--left " + quoted((dir_ / "silence.wav").string()));
    EXPECT_EQ(audio.status, 1) << audio.err;
    EXPECT_NE(audio.err.find("cannot be decoded (no video stream)"), std::string::npos) << audio.err;
}

TEST_F(TrackTool, UndecodableImageIsAnErrorUnlessSkipped)
{
    const std::string mono = "--left " + quoted(pattern("corrupt")) + " --particles 50";
    const RunResult stopped = run(mono);
    EXPECT_EQ(stopped.status, 1) << stopped.err;
    EXPECT_NE(stopped.err.find("frame 5 of 12"), std::string::npos) << stopped.err;
    EXPECT_NE(stopped.err.find("005.png"), std::string::npos) << stopped.err;
    EXPECT_NE(stopped.err.find("cannot be decoded"), std::string::npos) << stopped.err;

    const RunResult skipped = run(mono + " --skip-bad-frames");
    ASSERT_EQ(skipped.status, 0) << skipped.err;
    const std::vector<int> expected{0, 1, 2, 3, 4, 6, 7, 8, 9, 10, 11};
    EXPECT_EQ(frame_numbers(skipped.out), expected) << "lines keep the input's frame numbers";
    EXPECT_NE(skipped.err.find("frame 5 of 12"), std::string::npos) << skipped.err;
    EXPECT_NE(skipped.err.find("1 undecodable skipped"), std::string::npos) << skipped.err;

    // In stereo the pair is skipped, so the views stay paired by index.
    const RunResult stereo = run("--left " + quoted(pattern("corrupt")) + " --right " + quoted(pattern("right")) +
                                 " --particles 50 --max-frames 12 --skip-bad-frames");
    ASSERT_EQ(stereo.status, 0) << stereo.err;
    EXPECT_EQ(frame_numbers(stereo.out), expected);
    const RunResult stereo_stopped =
        run("--left " + quoted(pattern("right")) + " --right " + quoted(pattern("corrupt")) + " --particles 50");
    EXPECT_EQ(stereo_stopped.status, 1);
    EXPECT_NE(stereo_stopped.err.find("right input"), std::string::npos) << stereo_stopped.err;
    EXPECT_NE(stereo_stopped.err.find("frame 5 of 12"), std::string::npos) << stereo_stopped.err;
}

// The AVI cut in half ends inside a frame's JPEG. GStreamer's AVI demuxer rebuilds its index
// from the chunks that remain, so the count named is theirs (at most the 24 written), and the
// frame cut through is the undecodable one.
TEST_F(TrackTool, TruncatedVideoIsAnErrorUnlessSkipped)
{
    const std::string video = "--left " + quoted((dir_ / "cut.avi").string()) + " --particles 50";
    const RunResult stopped = run(video);
    EXPECT_EQ(stopped.status, 1) << stopped.err;
    std::smatch named;
    ASSERT_TRUE(std::regex_search(stopped.err, named, std::regex("frame ([0-9]+) of ([0-9]+) cannot be decoded")))
        << stopped.err;
    const std::size_t count = std::stoul(named[2].str());
    EXPECT_LT(std::stoul(named[1].str()), count);
    EXPECT_LE(count, static_cast<std::size_t>(kVideoFrames));

    const RunResult skipped = run(video + " --skip-bad-frames");
    ASSERT_EQ(skipped.status, 0) << skipped.err;
    const std::size_t lines = lines_of(skipped.out).size();
    EXPECT_GT(lines, 0u);
    EXPECT_LT(lines, count);
    EXPECT_NE(skipped.err.find(std::to_string(count - lines) + " undecodable skipped"), std::string::npos)
        << skipped.err;
}

TEST_F(TrackTool, OversizedFramesAreRefusedWithTheirSize)
{
    const RunResult wide = run("--left " + quoted(pattern("wide")));
    EXPECT_EQ(wide.status, 1);
    EXPECT_NE(wide.err.find("8193x40"), std::string::npos) << wide.err;
    EXPECT_NE(wide.err.find("8192x8192"), std::string::npos) << wide.err;
    EXPECT_TRUE(wide.out.empty());
    // Small files that declare huge images: refused from their headers, by the declared size.
    const RunResult png = run("--left " + quoted((dir_ / "claims.png").string()));
    EXPECT_EQ(png.status, 1);
    EXPECT_NE(png.err.find("30000x30000"), std::string::npos) << png.err;
    fs::create_directories(dir_ / "claims");
    fs::copy_file(dir_ / "claims.jpg", dir_ / "claims" / "000.jpg", fs::copy_options::overwrite_existing);
    const RunResult jpeg = run("--left " + quoted((dir_ / "claims" / "%03d.jpg").string()));
    EXPECT_EQ(jpeg.status, 1);
    EXPECT_NE(jpeg.err.find("30000x20000"), std::string::npos) << jpeg.err;
}

TEST_F(TrackTool, OutputErrorsNameTheOutput)
{
    const std::string input = "--left " + quoted(pattern("left")) + " --particles 50 --max-frames 3";
    const RunResult file = run(input + " --out /dev/full");
    EXPECT_EQ(file.status, 1);
    EXPECT_NE(file.err.find("'/dev/full'"), std::string::npos) << file.err;
    const RunResult piped = run(input, "/dev/full");
    EXPECT_EQ(piped.status, 1);
    EXPECT_NE(piped.err.find("standard output"), std::string::npos) << piped.err;
}

TEST_F(TrackTool, LinesAreWrittenWholeAsTheyAreMade)
{
    const char* exe = std::getenv("GESTURECAM_GESTURECAM_TRACK_EXE");
    ASSERT_NE(exe, nullptr);
    const fs::path out = dir_ / "watched.jsonl";
    const gc::test::LineWatch w = gc::test::watch_lines(
        {exe, "--left", pattern("left"), "--right", pattern("right"), "--particles", "2000", "--out", out.string()},
        out.string(), 8, std::chrono::seconds(60));
    ASSERT_TRUE(w.started);
    EXPECT_GT(w.looks, 0);
    EXPECT_TRUE(w.partial.empty()) << "a reader following the file saw part of a line, ending '"
                                   << w.partial.substr(w.partial.size() - std::min<std::size_t>(w.partial.size(), 40))
                                   << "'";
    ASSERT_FALSE(w.final_content.empty());
    EXPECT_EQ(w.final_content.back(), '\n') << "terminated: " << w.terminated;
    for (const std::string& line : lines_of(w.final_content)) EXPECT_NO_THROW((void)JsonReader::parse(line)) << line;
}

}  // namespace
