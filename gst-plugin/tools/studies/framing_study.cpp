// Not a test (it runs on the wall clock): the point-and-frame loop through GStreamer. headsim
// on loopback carries two live handscenesrc eyes; handtracker keeps the hand in view
// (steer=fixate) and its attended output frames what a pointing held for `dwell=1` s picks,
// the point `target-distance` along the ray. Each episode is one run of the pipeline with a
// fresh head and a rendered hand held still, aimed (handscenesrc `aim`) so that the point
// target-distance along its ray lies in the left view once the hand is centred.
//
//   framing_study [director] [EPISODES_PER_DISTANCE [FIRST_SEED [SECONDS]]]   (default 6, 1, 6 s)
//
// With `director`, a second simulated head (handtracker `director`, placed by the calibration
// file the study writes) frames the target instead of the crop, and the hand points to one
// side, 45-65 deg from straight ahead, so that its target lies outside the stereo views; the
// director's picture is judged from the pose its head reports every 10 ms, from the moment
// the pick's message comes off the bus.
//
// Per episode: the time from the pick (the tracker's `attended-target` message) until the
// crop holds the true target (the rendered ray's point at target-distance, projected with the
// pose each frame was rendered from) in its central third with the 500 mm region filling
// 75-125 % of its width, on that frame and every later one; and the share of frames the hand
// was tracked. Then p50/p95 per distance and over all.
#include "framing_episode.hpp"

#include <gst/gst.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

using gc::study::Episode;
using gc::study::EpisodeResult;

std::string load_average()
{
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

// The q-quantile (nearest rank) of `v`; a missed framing counts as infinitely late.
double quantile(std::vector<double> v, double q)
{
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const std::size_t k = std::size_t(std::ceil(q * double(v.size()))) - 1;
    return v[std::min(k, v.size() - 1)];
}

std::string seconds(double s) { return std::isfinite(s) ? std::to_string(s).substr(0, 4) + " s" : "missed"; }

struct Row {
    std::vector<double> to_framed_s;
    int episodes = 0, picked = 0, framed = 0;
    long frames = 0, tracked = 0;
};

void add(Row& row, const EpisodeResult& r)
{
    ++row.episodes;
    row.frames += r.frames;
    row.tracked += r.tracked;
    if (r.picked) ++row.picked;
    const double t = r.framed_after_s.value_or(std::numeric_limits<double>::infinity());
    if (std::isfinite(t)) ++row.framed;
    row.to_framed_s.push_back(t);
}

void print_row(const char* name, const Row& row)
{
    std::printf("| %s | %d | %d | %d | %s | %s | %.1f %% |\n", name, row.episodes, row.picked, row.framed,
                seconds(quantile(row.to_framed_s, 0.5)).c_str(), seconds(quantile(row.to_framed_s, 0.95)).c_str(),
                100.0 * double(row.tracked) / double(std::max(row.frames, 1L)));
}

}  // namespace

int main(int argc, char** argv)
{
    const bool director = argc > 1 && std::string(argv[1]) == "director";
    const int arg = director ? 2 : 1;
    const int per_distance = argc > arg ? std::atoi(argv[arg]) : 6;
    const unsigned first_seed = argc > arg + 1 ? unsigned(std::atoi(argv[arg + 1])) : 1;
    const double run_s = argc > arg + 2 ? std::atof(argv[arg + 2]) : 6.0;
    if (per_distance < 1 || run_s < 3.0) {
        std::fprintf(stderr, "usage: framing_study [director] [EPISODES_PER_DISTANCE [FIRST_SEED [SECONDS >= 3]]]\n");
        return 2;
    }
    g_setenv("GST_PLUGIN_PATH", GC_PLUGIN_DIR, FALSE);
    gst_init(&argc, &argv);
    std::printf("load average at the start: %s\n", load_average().c_str());
    std::map<int, Row> rows;
    Row all;
    for (const int distance : {1500, 2000, 2500, 3000}) {
        for (int k = 0; k < per_distance; ++k) {
            Episode e;
            e.seed = first_seed + unsigned(k);
            e.target_distance_mm = distance;
            e.direction = k;
            e.seconds = run_s;
            e.director = director;
            const EpisodeResult r = gc::study::run_episode(e);
            std::printf("  %d mm, seed %u, %s: %s; picked %s; framed %s after the pick (last frame: target at "
                        "%.2f, %.2f of the picture, region %.2f of its width); picked %+.1f deg right, %+.1f deg "
                        "down of the true target; tracked %d of %d pairs, a 3D ray on %d\n",
                        distance, e.seed, r.aim.c_str(), r.error.empty() ? "ran" : r.error.c_str(),
                        r.picked ? ("at " + std::to_string(r.pick_s).substr(0, 4) + " s").c_str() : "never",
                        seconds(r.framed_after_s.value_or(std::numeric_limits<double>::infinity())).c_str(),
                        r.last_placement[0], r.last_placement[1], r.last_placement[2], r.pick_error_deg[0],
                        r.pick_error_deg[1], r.tracked, r.frames, r.pointing);
            std::fflush(stdout);
            add(rows[distance], r);
            add(all, r);
        }
    }
    std::printf("load average at the end: %s\n\n", load_average().c_str());
    std::printf("| target-distance | episodes | picked | framed | p50 pick -> framed | p95 | hand tracked |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const auto& [distance, row] : rows) print_row((std::to_string(distance) + " mm").c_str(), row);
    print_row("all", all);
    return 0;
}
