// gesturecam-track end to end: a rendered stereo sequence written as PNG files goes in, JSON
// lines come out; wrong inputs and options give a non-zero status and a message naming them.
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "tools/json_reader.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using gc::tools::JsonReader;
using gc::tools::JsonValue;

namespace {

struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};

std::string read_text(const fs::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<std::string> lines_of(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    return lines;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Fast PNG writing: the test's time goes to tracking, not to compression.
bool write_png(const std::filesystem::path& p, const cv::Mat& image)
{
    return cv::imwrite(p.string(), image, {cv::IMWRITE_PNG_COMPRESSION, 1});
}

class TrackTool : public ::testing::Test {
protected:
    static constexpr int kFrames = 45;
    static constexpr int kFormatFrames = 20;

    static void SetUpTestSuite()
    {
        dir_ = fs::temp_directory_path() / ("gesturecam-track-test-" + std::to_string(::getpid()));
        fs::create_directories(dir_ / "left");
        fs::create_directories(dir_ / "right");
        fs::create_directories(dir_ / "short");
        fs::create_directories(dir_ / "small");
        fs::create_directories(dir_ / "bgra");
        fs::create_directories(dir_ / "grey16");
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
            scene.render(f, gc::Eye::Right, {}, frame);
            ASSERT_TRUE(write_png(dir_ / "right" / name, frame));
            if (f < 5) {
                ASSERT_TRUE(write_png(dir_ / "short" / name, frame));
            }
        }
    }

    static void TearDownTestSuite()
    {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    static std::string pattern(const char* folder) { return (dir_ / folder / "%03d.png").string(); }

    // Runs the tool with `args` (already shell-quoted where needed).
    static RunResult run(const std::string& args)
    {
        const char* exe = std::getenv("GESTURECAM_GESTURECAM_TRACK_EXE");
        if (exe == nullptr) {
            ADD_FAILURE() << "GESTURECAM_GESTURECAM_TRACK_EXE is not set";
            return {};
        }
        const fs::path out = dir_ / "stdout.txt";
        const fs::path err = dir_ / "stderr.txt";
        const std::string cmd = quoted(exe) + " " + args + " > " + quoted(out.string()) + " 2> " +
                                quoted(err.string());
        const int raw = std::system(cmd.c_str());
        RunResult r;
        r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        r.out = read_text(out);
        r.err = read_text(err);
        return r;
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
        if (state != "tracking")
            continue;
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
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("small")) +
                            " --out " + quoted(out.string()));
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
    const RunResult r = run("--left " + quoted(pattern("left")) + " --right " + quoted(pattern("short")) +
                            " --particles 50");
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
}

}  // namespace
