// Not a test: the element-level head-jump run (element_chaos.hpp) over many frames, with
// the process's RSS along the way. Prints the jumps, how many were judged (the hand in
// both views for 60 frames after) and found again within 30 frames, and the RSS after
// 1000, 5000 and the last frame.
//
//   element_chaos [FRAMES [SEED [head [FPS]]]]
//
// Default 10000 frames, seed 1, 30 frames/s; exit 1 if a check fails. Without `head` a GstController
// moves the sources' rig and nothing tells handtracker; with `head` a simulated head on
// loopback moves (head_jumper.hpp), the live sources render from it and handtracker reads it.
// GESTURECAM_CHAOS_TRACE=1 prints every judged jump's frames, not only those not found again.
#include "element_chaos.hpp"
#include "head_jumper.hpp"

#include <glib/gstdio.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using namespace gc::chaos;

std::string load_average()
{
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return one + " " + five + " " + fifteen;
}

// Frame by frame from the jump: T tracking on the hand, t tracking elsewhere, . not,
// - no JSON line (a live tracker that fell behind skips frames).
std::string states_after(const Outcome& o, const Run& run, const std::vector<Tracked>& tracked)
{
    std::string states;
    for (int f = o.frame; f < o.frame + kJudgedVisibleFrames && f < int(tracked.size()); ++f) {
        const Tracked& t = tracked[size_t(f)];
        states += !t.line ? '-' : !t.tracking ? '.' : overlap(t.bbox, run.left[size_t(f)].bbox) ? 'T' : 't';
    }
    return states;
}

// Prints the figures; true when every judged jump was found again.
bool report(int frames, const std::vector<RigJump>& jumps, const Run& run, const std::vector<Tracked>& tracked)
{
    const bool trace = g_getenv("GESTURECAM_CHAOS_TRACE") != nullptr;
    int judged = 0, found = 0, stale = 0;
    std::vector<int> delays;
    for (const Outcome& o : judge(jumps, run, tracked)) {
        if (!o.judged()) continue;
        ++judged;
        if (o.found()) {
            ++found;
            delays.push_back(o.found_after);
        }
        const std::string states = states_after(o, run, tracked);
        // Not found: a stale lock when the tracker was on something else more than on nothing.
        const std::string first = states.substr(0, kFoundWithin + 1);
        if (!o.found() && std::count(first.begin(), first.end(), 't') > std::count(first.begin(), first.end(), '.'))
            ++stale;
        if (!o.found() || trace)
            std::printf("jump at frame %d: %s within %d frames: %s\n", o.frame, o.found() ? "found" : "not found again",
                        kFoundWithin, states.c_str());
    }
    std::sort(delays.begin(), delays.end());
    const long lines = std::count_if(tracked.begin(), tracked.end(), [](const Tracked& t) { return t.line; });
    std::printf("%s after %.1f s (%.1f stereo fps), %ld JSON lines, %zu warnings%s%s\n", run.eos ? "EOS" : "no EOS",
                run.seconds, frames / run.seconds, lines, run.warnings.size(),
                run.error.empty() ? "" : ", error: ", run.error.c_str());
    std::printf("%d frames, %zu jumps; %d left the hand in both views for %d+ frames, found again within %d frames "
                "after %d (median %d, max %d frames)\n",
                frames, jumps.size(), judged, kJudgedVisibleFrames, kFoundWithin, found,
                delays.empty() ? -1 : delays[delays.size() / 2], delays.empty() ? -1 : delays.back());
    std::printf("not found again: %d stale locks (tracking off the hand more than not tracking), %d others\n", stale,
                judged - found - stale);
    for (const std::string& warning : run.warnings) std::printf("warning: %s\n", warning.c_str());
    for (const auto& [buffers, kib] : run.rss_kib) std::printf("RSS after frame %d: %.1f MB\n", buffers, kib / 1024.0);
    return found == judged && judged > 0;
}

}  // namespace

int main(int argc, char** argv)
{
    gst_init(&argc, &argv);
    const int frames = argc > 1 ? std::atoi(argv[1]) : 10000;
    const unsigned seed = argc > 2 ? unsigned(std::atoi(argv[2])) : 1u;
    const bool with_head = argc > 3 && std::string(argv[3]) == "head";
    // A live pipeline keeps its frame rate only where the tracker keeps up with it.
    const int fps = argc > 4 ? std::max(1, std::atoi(argv[4])) : kFps;
    const std::string json = std::string(g_get_tmp_dir()) + "/element-chaos-" + std::to_string(getpid()) + ".jsonl";
    std::unique_ptr<gc::loopback::RunningHead> head;
    if (with_head) head = std::make_unique<gc::loopback::RunningHead>(fast_head());
    GError* err = nullptr;
    GstElement* pipeline =
        gst_parse_launch(pipeline_description(frames, seed, json, head ? head->uri() : "", fps).c_str(), &err);
    if (!pipeline) {
        std::fprintf(stderr, "element_chaos: %s\n", err ? err->message : "cannot build the pipeline");
        return 2;
    }
    const std::vector<RigJump> jumps = random_jumps(frames, seed);
    std::unique_ptr<HeadJumper> jumper;
    if (head)
        jumper = std::make_unique<HeadJumper>(pipeline, jumps, head->uri(), fps);
    else if (!drive_rig(pipeline, jumps))
        return 2;
    std::printf("load average at the start: %s; %d frames/s%s\n", load_average().c_str(), fps,
                (head ? ", live, head on " + head->uri() : std::string()).c_str());
    const Run run = play(pipeline, {1, 1000, 5000, frames}, 3600 * GST_SECOND);
    const int moves = jumper ? jumper->sent() : 0;
    jumper.reset();
    gst_object_unref(pipeline);
    const std::vector<Tracked> tracked = read_tracked(json, run);
    g_remove(json.c_str());
    std::printf("load average at the end: %s; head moves sent: %d\n", load_average().c_str(), moves);
    const bool found_all = report(frames, jumps, run, tracked);
    gst_deinit();  // lets GST_TRACERS=leaks report what is still alive
    return run.eos && run.error.empty() && found_all ? 0 : 1;
}
