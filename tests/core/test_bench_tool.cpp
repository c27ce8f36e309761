// gesturecam-bench: the quick smoke run prints well-formed JSON lines covering every table (both
// detectors, the stereo rows, the real pair), with figures in their valid ranges; bad options
// are rejected.
#include "tool_run.hpp"
#include "tools/json_reader.hpp"
#include "tools/real_pair.hpp"
#include "tools/tool_version.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using gc::tools::JsonReader;
using gc::tools::JsonValue;

namespace {

using gc_test::read_text;
using gc_test::RunResult;

RunResult run_bench(const std::string& args)
{
    const char* exe = std::getenv("GESTURECAM_GESTURECAM_BENCH_EXE");
    if (exe == nullptr) {
        ADD_FAILURE() << "GESTURECAM_GESTURECAM_BENCH_EXE is not set";
        return {};
    }
    const fs::path base = fs::temp_directory_path() / ("gesturecam-bench-test-" + std::to_string(::getpid()));
    const std::string out = base.string() + ".out", err = base.string() + ".err";
    const std::string cmd = "'" + std::string(exe) + "' " + args + " > '" + out + "' 2> '" + err + "'";
    const int raw = std::system(cmd.c_str());
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    fs::remove(out);
    fs::remove(err);
    return r;
}

bool in_range(const JsonValue& v, double lo, double hi)
{
    return v.is_number() && v.number() >= lo && v.number() <= hi;
}

using Rows = std::map<std::string, std::vector<JsonValue>>;

// A JSON run's lines by kind.
Rows json_rows(const std::string& args)
{
    Rows by_kind;
    const RunResult r = run_bench(args + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
        JsonValue v;
        EXPECT_NO_THROW(v = JsonReader::parse(line)) << line;
        EXPECT_TRUE(v.has("kind")) << line;
        if (v.has("kind")) by_kind[v["kind"].string()].push_back(v);
    }
    return by_kind;
}

// The quick run's JSON lines by kind; parsed once for the tests below.
const Rows& quick_json_rows()
{
    static const Rows rows = json_rows("--quick");
    return rows;
}

std::vector<JsonValue> rows_of(const std::string& kind)
{
    const Rows& rows = quick_json_rows();
    const auto it = rows.find(kind);
    return it == rows.end() ? std::vector<JsonValue>{} : it->second;
}

TEST(BenchTool, QuickJsonRunCoversTheSyntheticTables)
{
    const std::vector<JsonValue> machine = rows_of("machine");
    ASSERT_EQ(machine.size(), 1u);
    EXPECT_GE(machine[0]["cores"].number(), 1);
    const std::vector<JsonValue> baseline = rows_of("baseline");
    ASSERT_EQ(baseline.size(), 1u);
    EXPECT_TRUE(in_range(baseline[0]["convert_ms"], 0.0, 1000.0));

    // --quick: scenes clean and heavy, 50 and 200 particles, each with both detectors.
    std::set<std::tuple<std::string, std::string, int>> seen;
    for (const JsonValue& row : rows_of("tracker")) {
        seen.insert({row["detector"].string(), row["scene"].string(), static_cast<int>(row["particles"].number())});
        EXPECT_TRUE(in_range(row["mean_iou"], 0.0, 1.0));
        EXPECT_TRUE(in_range(row["tracked_fraction"], 0.0, 1.0));
        EXPECT_TRUE(in_range(row["ms_per_frame"], 0.0, 10000.0));
        EXPECT_TRUE(in_range(row["cpu_ms_per_frame"], 1e-6, 10000.0));
        EXPECT_TRUE(in_range(row["skin_pct"], 0.0, 100.0));
        EXPECT_TRUE(row["snr_db"].is_number() || row["snr_db"].is_null());
    }
    std::set<std::tuple<std::string, std::string, int>> expected;
    for (const char* detector : {"learned", "motion"})
        for (const char* scene : {"clean", "heavy"})
            for (int particles : {50, 200}) expected.insert({detector, scene, particles});
    EXPECT_EQ(seen, expected);
    EXPECT_EQ(rows_of("tracker").size(), expected.size());

    std::set<std::string> peers;
    for (const JsonValue& p : rows_of("peer")) {
        peers.insert(p["tracker"].string());
        EXPECT_EQ(p["detector"].string(), "learned");
        EXPECT_TRUE(in_range(p["box_iou"], 0.0, 1.0));
        EXPECT_TRUE(in_range(p["ms_per_frame"], 0.0, 10000.0));
    }
    EXPECT_EQ(peers, (std::set<std::string>{"gesturecam", "kcf", "csrt", "medianflow", "camshift"}));
}

// One stereo row per detector; the network runs only in the learned mode.
TEST(BenchTool, QuickJsonRunHasAStereoRowPerDetector)
{
    std::map<std::string, JsonValue> by_detector;
    for (const JsonValue& s : rows_of("stereo")) by_detector[s["detector"].string()] = s;
    ASSERT_EQ(rows_of("stereo").size(), 2u);
    ASSERT_EQ(by_detector.size(), 2u);
    for (const auto& [detector, s] : by_detector) {
        EXPECT_TRUE(in_range(s["pipeline_fps"], 0.0, 1e6)) << detector;
        EXPECT_TRUE(in_range(s["rendering_fps"], 0.0, 1e6)) << detector;
        EXPECT_TRUE(in_range(s["cpu_ms_per_frame"], 1e-6, 1e6)) << detector;
        EXPECT_TRUE(in_range(s["rendering_cpu_ms_per_frame"], 1e-6, 1e6)) << detector;
        EXPECT_TRUE(in_range(s["valid_3d"], 0.0, s["frames"].number())) << detector;
    }
    EXPECT_TRUE(in_range(by_detector["learned"]["models_share"], 1e-9, 1.0));
    EXPECT_TRUE(in_range(by_detector["motion"]["models_share"], 0.0, 0.0));
}

// One row per learned model: both ways timed, their outputs the same but for the order of
// floating-point sums.
TEST(BenchTool, QuickJsonRunTimesEachLearnedModelBothWays)
{
    std::set<std::string> models;
    for (const JsonValue& m : rows_of("models")) {
        models.insert(m["model"].string());
        EXPECT_TRUE(in_range(m["opencv_cpu_ms"], 1e-6, 1e6)) << m["model"].string();
        EXPECT_TRUE(in_range(m["product_cpu_ms"], 1e-6, 1e6)) << m["model"].string();
        EXPECT_TRUE(in_range(m["ratio"], 1e-6, 1e6)) << m["model"].string();
        EXPECT_TRUE(in_range(m["max_abs_diff"], 0.0, 1e-2)) << m["model"].string();
    }
    EXPECT_EQ(models, (std::set<std::string>{"palm_detection.onnx", "hand_landmark.onnx"}));
    EXPECT_EQ(rows_of("models").size(), 2u);
}

// --quick tracks the real pair's first 40 frames: 26 of them (14-39) point.
TEST(BenchTool, QuickJsonRunHasTheRealPairForEachDetector)
{
    std::set<std::pair<std::string, std::string>> views;
    for (const JsonValue& v : rows_of("real_view")) {
        const std::string detector = v["detector"].string(), view = v["view"].string();
        views.insert({detector, view});
        EXPECT_EQ(v["pointing_frames"].number(), 26) << detector << ' ' << view;
        for (const char* share : {"coverage", "within_30px", "models_share", "pointing_coverage"})
            EXPECT_TRUE(in_range(v[share], 0.0, 1.0)) << detector << ' ' << view << ' ' << share;
        if (detector == "learned") {
            // The landmark model sees this hand: the fingertip is found and lands near it.
            EXPECT_GE(v["pointing_coverage"].number(), 0.5) << view;
            EXPECT_TRUE(in_range(v["pointing_median_px"], 0.0, 30.0)) << view;
            EXPECT_GT(v["models_share"].number(), 0.0) << view;
        } else {
            EXPECT_EQ(v["models_share"].number(), 0.0) << view;
        }
    }
    EXPECT_EQ(views, (std::set<std::pair<std::string, std::string>>{
                         {"learned", "left"}, {"learned", "right"}, {"motion", "left"}, {"motion", "right"}}));

    std::set<std::string> detectors;
    for (const JsonValue& p : rows_of("real_pair")) {
        const std::string detector = p["detector"].string();
        detectors.insert(detector);
        EXPECT_EQ(p["frames"].number(), 40) << detector;
        EXPECT_EQ(p["noise_sd"].number(), 0.0) << detector;  // the recording as it is
        EXPECT_FALSE(std::get<bool>(p["bright_window"].v)) << detector;
        EXPECT_EQ(p["pointing_frames"].number(), 26) << detector;
        EXPECT_TRUE(in_range(p["ray_coverage"], 0.0, 1.0)) << detector;
        EXPECT_TRUE(in_range(p["false_pointing"], 0.0, 1.0)) << detector;
        EXPECT_TRUE(in_range(p["ms_per_frame"], 1e-6, 10000.0)) << detector;
        EXPECT_TRUE(in_range(p["cpu_ms_per_frame"], 1e-6, 10000.0)) << detector;
    }
    EXPECT_EQ(detectors, (std::set<std::string>{"learned", "motion"}));
    EXPECT_EQ(rows_of("real_pair").size(), 2u);

    // The view alone through each narrower window, per detector.
    std::set<std::pair<std::string, std::string>> windows;
    for (const JsonValue& w : rows_of("real_window")) {
        const std::string detector = w["detector"].string(), window = w["window"].string();
        windows.insert({detector, window});
        EXPECT_TRUE(in_range(w["reference_frames"], 1.0, 40.0)) << detector << ' ' << window;
        EXPECT_TRUE(in_range(w["cut_frames"], 0.0, w["reference_frames"].number())) << detector << ' ' << window;
        for (const char* share : {"coverage", "within_30px", "models_share"})
            EXPECT_TRUE(in_range(w[share], 0.0, 1.0)) << detector << ' ' << window << ' ' << share;
        if (detector == "learned") {
            EXPECT_GE(w["coverage"].number(), 0.5) << window;
        }
    }
    EXPECT_EQ(windows.size(), 2 * std::size(gc::tools::kEdgeWindows));
}

// Over several seeds each real-pair figure is the mean of the per-seed figures (one seed's
// figures move with the tracker's random path alone). The JSON rounds to 3 decimals (shares)
// or 1 (pixels, degrees), so the mean of two printed figures may be off by that much.
TEST(BenchTool, RealPairFiguresAreMeansOverTheSeeds)
{
    const std::string args =
        "--quick --no-peers --detectors learned --scenes clean --particles 20 --frames 10 --seeds ";
    const Rows one = json_rows(args + "1"), two = json_rows(args + "2"), both = json_rows(args + "1,2");
    struct Figure {
        const char* kind;
        const char* field;
        double rounding;
    };
    const Figure figures[] = {{"real_pair", "ray_coverage", 1e-3}, {"real_pair", "angle_median_deg", 0.1},
                              {"real_pair", "angle_p90_deg", 0.1}, {"real_view", "median_px", 0.1},
                              {"real_view", "models_share", 1e-3}, {"real_window", "median_px", 0.1},
                              {"real_window", "within_30px", 1e-3}};
    int differing = 0;
    for (const Figure& f : figures) {
        SCOPED_TRACE(std::string(f.kind) + " " + f.field);
        ASSERT_EQ(one.count(f.kind), 1u);
        ASSERT_EQ(two.count(f.kind), 1u);
        ASSERT_EQ(both.count(f.kind), 1u);
        const JsonValue &a = one.at(f.kind).front(), &b = two.at(f.kind).front(), &ab = both.at(f.kind).front();
        EXPECT_EQ(ab["seeds"].string(), "1,2");
        const double mean = (a[f.field].number() + b[f.field].number()) / 2;
        EXPECT_NEAR(ab[f.field].number(), mean, f.rounding + 1e-9);
        differing += a[f.field].number() != b[f.field].number();
    }
    // The check means something only if the seeds' figures differ.
    EXPECT_GE(differing, 2);
}

std::size_t count(const std::string& text, const std::string& what)
{
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

TEST(BenchTool, MarkdownTablesByDefault)
{
    const RunResult r = run_bench("--quick --no-peers --scenes clean --particles 20,100 --frames 20 --real-frames 20");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("machine: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| scene | skin % | particles | SNR dB |"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("| kcf |"), std::string::npos) << "--no-peers";
    EXPECT_NE(r.out.find("pipeline frames/s"), std::string::npos) << r.out;
    // Two particle rows for the one scene, in each detector's table.
    EXPECT_EQ(count(r.out, "### learned detector"), 1u) << r.out;
    EXPECT_EQ(count(r.out, "### motion detector"), 1u) << r.out;
    EXPECT_EQ(count(r.out, "| clean | "), 4u) << r.out;
    EXPECT_EQ(count(r.out, "## Real pair"), 1u) << r.out;
    for (const char* row : {"| learned | left | ", "| learned | right | ", "| motion | left | ", "| motion | right | "})
        EXPECT_EQ(count(r.out, row), 1u) << row << '\n' << r.out;
    // Stereo and the real pair's 3D table: one row per detector each; the windows' table
    // one per detector and window.
    const std::size_t rows = 2 + std::size(gc::tools::kEdgeWindows);
    EXPECT_EQ(count(r.out, "| learned | "), 2 + rows) << r.out;
    EXPECT_EQ(count(r.out, "| motion | "), 2 + rows) << r.out;
}

TEST(BenchTool, OneDetectorAndNoRealPair)
{
    const RunResult r =
        run_bench("--quick --no-peers --no-real --detectors motion --scenes clean --particles 20 --frames 20");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count(r.out, "### motion detector"), 1u) << r.out;
    EXPECT_EQ(r.out.find("### learned"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("| learned |"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("Real pair"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("Learned models"), std::string::npos) << "no model timing without the learned detector";
    EXPECT_EQ(count(r.out, "| motion | "), 1u) << "one stereo row\n" << r.out;
}

TEST(BenchTool, RejectsBadOptions)
{
    for (const char* args : {"--particles 0", "--scenes clean,nowhere", "--runs x", "--particles 20,,50", "--bogus",
                             "--detectors learned,blob", "--real-frames 0", "--no-real=1", "--real-noise -1",
                             "--real-noise x", "--real-tracking-width 10"}) {
        const RunResult r = run_bench(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_FALSE(r.err.empty()) << args;
    }
    const RunResult r = run_bench("--scenes clean,nowhere");
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
    // One line that points at --help, not the whole usage.
    EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;
    EXPECT_NE(r.err.find("--help"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("usage:"), std::string::npos) << r.err;
    // A named real pair folder that is not there fails before anything is measured.
    const RunResult missing = run_bench("--quick --real /nonexistent/handpose3d");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("/nonexistent/handpose3d"), std::string::npos) << missing.err;
    EXPECT_EQ(missing.err.find("seed"), std::string::npos) << "measured before failing: " << missing.err;
}

TEST(BenchTool, AnswersVersionAndHelp)
{
    const RunResult version = run_bench("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_EQ(version.out, "gesturecam-bench " + std::string(GC_TOOL_VERSION) + "\n");
    const RunResult help = run_bench("-h");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("--no-peers"), std::string::npos) << help.out;
}

}  // namespace
