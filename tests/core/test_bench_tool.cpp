// gesturecam-bench: the quick smoke run prints well-formed JSON lines covering every table, with
// figures in their valid ranges; bad options are rejected.
#include "tools/json_reader.hpp"

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

TEST(BenchTool, QuickJsonRunCoversEveryTable)
{
    const RunResult r = run_bench("--quick --json");
    ASSERT_EQ(r.status, 0) << r.err;
    std::map<std::string, std::vector<JsonValue>> by_kind;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
        JsonValue v;
        ASSERT_NO_THROW(v = JsonReader::parse(line)) << line;
        ASSERT_TRUE(v.has("kind")) << line;
        by_kind[v["kind"].string()].push_back(v);
    }
    ASSERT_EQ(by_kind["machine"].size(), 1u);
    EXPECT_GE(by_kind["machine"][0]["cores"].number(), 1);
    ASSERT_EQ(by_kind["baseline"].size(), 1u);
    EXPECT_TRUE(in_range(by_kind["baseline"][0]["convert_ms"], 0.0, 1000.0));

    // --quick: scenes clean and heavy, 50 and 200 particles.
    const std::vector<JsonValue>& rows = by_kind["tracker"];
    ASSERT_EQ(rows.size(), 4u);
    std::set<std::pair<std::string, int>> seen;
    for (const JsonValue& row : rows) {
        seen.insert({row["scene"].string(), static_cast<int>(row["particles"].number())});
        EXPECT_TRUE(in_range(row["mean_iou"], 0.0, 1.0));
        EXPECT_TRUE(in_range(row["tracked_fraction"], 0.0, 1.0));
        EXPECT_TRUE(in_range(row["ms_per_frame"], 0.0, 10000.0));
        EXPECT_TRUE(in_range(row["skin_pct"], 0.0, 100.0));
        EXPECT_TRUE(row["snr_db"].is_number() || row["snr_db"].is_null());
    }
    EXPECT_EQ(seen, (std::set<std::pair<std::string, int>>{
                        {"clean", 50}, {"clean", 200}, {"heavy", 50}, {"heavy", 200}}));

    std::set<std::string> peers;
    for (const JsonValue& p : by_kind["peer"]) {
        peers.insert(p["tracker"].string());
        EXPECT_TRUE(in_range(p["box_iou"], 0.0, 1.0));
        EXPECT_TRUE(in_range(p["ms_per_frame"], 0.0, 10000.0));
    }
    EXPECT_EQ(peers, (std::set<std::string>{"gesturecam", "kcf", "csrt", "medianflow", "camshift"}));

    ASSERT_EQ(by_kind["stereo"].size(), 1u);
    const JsonValue& s = by_kind["stereo"][0];
    EXPECT_TRUE(in_range(s["pipeline_fps"], 0.0, 1e6));
    EXPECT_TRUE(in_range(s["valid_3d"], 0.0, s["frames"].number()));
}

TEST(BenchTool, MarkdownTablesByDefault)
{
    const RunResult r = run_bench("--quick --no-peers --scenes clean --particles 20,100");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("machine: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| scene | skin % | particles | SNR dB |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| clean | "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("| kcf |"), std::string::npos) << "--no-peers";
    EXPECT_NE(r.out.find("pipeline frames/s"), std::string::npos) << r.out;
    // Two particle rows for the one scene.
    std::size_t rows = 0;
    for (std::size_t at = r.out.find("| clean | "); at != std::string::npos; at = r.out.find("| clean | ", at + 1))
        ++rows;
    EXPECT_EQ(rows, 2u);
}

TEST(BenchTool, RejectsBadOptions)
{
    for (const char* args : {"--particles 0", "--scenes clean,nowhere", "--runs x", "--particles 20,,50",
                             "--bogus"}) {
        const RunResult r = run_bench(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_FALSE(r.err.empty()) << args;
    }
    const RunResult r = run_bench("--scenes clean,nowhere");
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
}

}  // namespace
