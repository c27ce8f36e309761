// Not a test: the element-level head-jump run (element_chaos.hpp) over many frames, with
// the process's RSS along the way. Prints the jumps, how many were judged (the hand in
// both views for 60 frames after) and found again within 30 frames, and the RSS after
// 1000, 5000 and the last frame.
//
//   element_chaos [FRAMES [SEED]]      (default 10000 frames, seed 1; exit 1 if a check fails)
#include "element_chaos.hpp"

#include <glib/gstdio.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>
#include <vector>

int main(int argc, char** argv)
{
    gst_init(&argc, &argv);
    const int frames = argc > 1 ? std::atoi(argv[1]) : 10000;
    const unsigned seed = argc > 2 ? unsigned(std::atoi(argv[2])) : 1u;
    const std::string json = std::string(g_get_tmp_dir()) + "/element-chaos-" + std::to_string(getpid()) + ".jsonl";
    GError* err = nullptr;
    GstElement* pipeline = gst_parse_launch(gc::chaos::pipeline_description(frames, seed, json).c_str(), &err);
    if (!pipeline) {
        std::fprintf(stderr, "element_chaos: %s\n", err ? err->message : "cannot build the pipeline");
        return 2;
    }
    const std::vector<gc::chaos::RigJump> jumps = gc::chaos::random_jumps(frames, seed);
    if (!gc::chaos::drive_rig(pipeline, jumps)) return 2;
    const gc::chaos::Run run = gc::chaos::play(pipeline, {1, 1000, 5000, frames}, 3600 * GST_SECOND);
    gst_object_unref(pipeline);
    const std::vector<gc::chaos::Tracked> tracked = gc::chaos::read_tracked(json);
    g_remove(json.c_str());

    int judged = 0, found = 0;
    std::vector<int> delays;
    for (const gc::chaos::Outcome& o : gc::chaos::judge(jumps, run, tracked)) {
        if (!o.judged()) continue;
        ++judged;
        if (o.found()) {
            ++found;
            delays.push_back(o.found_after);
        } else {
            // Frame by frame from the jump: T tracking on the hand, t tracking elsewhere, . not.
            std::string states;
            for (int f = o.frame; f < o.frame + gc::chaos::kJudgedVisibleFrames && f < int(tracked.size()); ++f)
                states += !tracked[size_t(f)].tracking                                            ? '.'
                          : gc::chaos::overlap(tracked[size_t(f)].bbox, run.left[size_t(f)].bbox) ? 'T'
                                                                                                  : 't';
            std::printf("jump at frame %d: not found again within %d frames: %s\n", o.frame, gc::chaos::kFoundWithin,
                        states.c_str());
        }
    }
    std::sort(delays.begin(), delays.end());
    std::printf("%s after %.1f s (%.1f stereo fps), %zu JSON lines, %zu warnings%s%s\n", run.eos ? "EOS" : "no EOS",
                run.seconds, frames / run.seconds, tracked.size(), run.warnings.size(),
                run.error.empty() ? "" : ", error: ", run.error.c_str());
    std::printf("%d frames, %zu jumps; %d left the hand in both views for %d+ frames, found again within %d frames "
                "after %d (median %d, max %d frames)\n",
                frames, jumps.size(), judged, gc::chaos::kJudgedVisibleFrames, gc::chaos::kFoundWithin, found,
                delays.empty() ? -1 : delays[delays.size() / 2], delays.empty() ? -1 : delays.back());
    for (const std::string& warning : run.warnings) std::printf("warning: %s\n", warning.c_str());
    for (const auto& [buffers, kib] : run.rss_kib) std::printf("RSS after frame %d: %.1f MB\n", buffers, kib / 1024.0);
    gst_deinit();  // lets GST_TRACERS=leaks report what is still alive
    return run.eos && run.error.empty() && found == judged && judged > 0 ? 0 : 1;
}
