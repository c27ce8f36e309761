// Not a test: the tracker under a head that jumps. For N stereo frames of a rendered scene
// the head's pose jumps to a random pan/tilt (0-180 deg away; past the rendered room's wall
// the view shows no hand) every 1-30 frames; the
// tracker gets each jump as the camera motion it causes (as the element's head link does),
// steering off. Prints, for every jump after which the hand stays in view for 60 frames or
// more, whether and how fast it was found again (tracking with its left box on the hand's),
// the stale locks (tracking something else instead), and the process's RSS over the run.
//
//   head_chaos [FRAMES [SEED [TRACE]]]  (default 10000 frames, seed 1; exit 1 if a check fails)
// With TRACE, each missed jump's first 60 frames are printed: T on the hand, t elsewhere,
// . not tracking, x hand out of view.
#include "sim/scene.hpp"
#include "stereo/camera_motion.hpp"
#include "tracker/pointing_tracker.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// The head turns at most this far each way.
constexpr double kMaxPan = 90.0;
constexpr double kMaxTilt = 90.0;

// One eye's view at `pose`: the rendered room, or, where the head looks past the room's
// wall, a view of somewhere else without the hand (seeded noise).
void view(const gc::sim::Scene& scene, int frame, gc::Eye eye, const gc::HeadPose& pose, cv::Mat& bgr,
          gc::sim::EyeTruth& truth)
{
    try {
        scene.render(frame, eye, pose, bgr, &truth);
    } catch (const std::invalid_argument&) {
        cv::theRNG().state = std::uint64_t(frame) * 2 + int(eye) + 1;
        cv::randu(bgr, cv::Scalar::all(40), cv::Scalar::all(200));
        truth = gc::sim::EyeTruth{};
    }
}

long rss_kib()
{
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return -1;
}

gc::ImageMotion motion_of(const gc::StereoCalibration& cal, gc::Eye eye, const gc::HeadPose& before,
                          const gc::HeadPose& after)
{
    const cv::Point2d centre(cal.M1(0, 2), cal.M1(1, 2));
    try {
        return gc::camera_motion(cal, eye, before, after, centre, 1000.0);
    } catch (const std::domain_error&) {
        return {};  // the view turned away entirely: nothing to predict, as the head link says
    }
}

struct Jump {
    int frame = 0;
    int visible_after = 0;  // consecutive frames with the hand in both views after the jump
    int found_after = -1;   // frames until tracking on the hand, -1: never
    int elsewhere = 0;      // of the first 31 frames, tracking off the hand
    int untracked = 0;      // ... and not tracking
    std::string trace;      // of the first 61 frames
};

bool overlap(const cv::Rect& a, const cv::Rect& b) { return (a & b).area() > 0; }

}  // namespace

int main(int argc, char** argv)
{
    const int frames = argc > 1 ? std::atoi(argv[1]) : 10000;
    const unsigned seed = argc > 2 ? unsigned(std::atoi(argv[2])) : 1u;
    gc::sim::SceneConfig config;
    config.preset = gc::sim::Preset::Light;
    config.motion = gc::sim::Motion::Mixed;
    config.seed = seed;
    const gc::sim::Scene scene(config);
    const gc::StereoCalibration cal = scene.calibration();
    gc::TrackerParams params;
    params.seed = seed;
    gc::PointingTracker tracker(params, cal);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> gap(1, 30);
    std::uniform_real_distribution<double> away(0.0, 180.0), share(0.0, 1.0), sign(-1.0, 1.0);

    gc::HeadPose pose, home;
    std::vector<Jump> jumps;
    cv::Mat left(config.height, config.width, CV_8UC3), right(config.height, config.width, CV_8UC3);
    gc::sim::EyeTruth tl, tr;
    long rss_first = -1, rss_peak = 0;
    int next_jump = gap(rng);
    for (int f = 0; f < frames; ++f) {
        gc::HeadPose before = pose;
        if (f == next_jump) {
            // A jump of up to `away` degrees split between pan and tilt; most land near
            // home, so
            // that the hand is often still in view afterwards.
            const double size = away(rng) * (share(rng) < 0.7 ? 0.1 : 1.0), split = share(rng);
            pose.pan_deg = std::clamp(home.pan_deg + sign(rng) * size * split, -kMaxPan, kMaxPan);
            pose.tilt_deg = std::clamp(home.tilt_deg + sign(rng) * size * (1.0 - split), -kMaxTilt, kMaxTilt);
            jumps.push_back(Jump{f, 0, -1, 0, 0, {}});
            next_jump = f + gap(rng);
        }
        view(scene, f, gc::Eye::Left, pose, left, tl);
        view(scene, f, gc::Eye::Right, pose, right, tr);
        const gc::FrameResult& r =
            tracker.process_stereo(left, right, -1, pose, motion_of(cal, gc::Eye::Left, before, pose),
                                   motion_of(cal, gc::Eye::Right, before, pose));
        // Later jumps may keep the hand in view: every jump of the last 60 frames is followed.
        for (auto j = jumps.rbegin(); j != jumps.rend() && f - j->frame <= 60; ++j) {
            const int since = f - j->frame;
            const bool in_view = tl.visible && tr.visible;
            if (since == j->visible_after && in_view) ++j->visible_after;
            const bool tracking = r.state == gc::TrackState::Tracking;
            const bool on_hand = tracking && overlap(r.left.bbox, tl.bbox);
            if (j->found_after < 0 && on_hand) j->found_after = since;
            if (since <= 30 && !tracking) ++j->untracked;
            if (since <= 30 && tracking && !on_hand) ++j->elsewhere;
            j->trace += !in_view ? 'x' : on_hand ? 'T' : tracking ? 't' : '.';
        }
        const long rss = rss_kib();
        if (f == 500) rss_first = rss;
        rss_peak = std::max(rss_peak, rss);
    }
    const bool trace = argc > 3;
    int judged = 0, found = 0, stale = 0;
    std::vector<int> delays;
    for (const Jump& j : jumps) {
        if (j.visible_after < 60) continue;
        ++judged;
        if (j.found_after >= 0 && j.found_after <= 30) {
            ++found;
            delays.push_back(j.found_after);
            continue;
        }
        stale += j.elsewhere > j.untracked;
        if (trace) std::printf("jump at frame %d: %s\n", j.frame, j.trace.c_str());
    }
    std::sort(delays.begin(), delays.end());
    std::printf("%d frames, %zu jumps; %d left the hand in view for 60+ frames, found again within 30 frames "
                "after %d (median %d frames)\n",
                frames, jumps.size(), judged, found, delays.empty() ? -1 : delays[delays.size() / 2]);
    std::printf("not found again: %d stale locks (tracking off the hand more than not tracking), %d others\n", stale,
                judged - found - stale);
    std::printf("RSS %ld KiB at frame 500, peak %ld KiB, at the end %ld KiB\n", rss_first, rss_peak, rss_kib());
    return found == judged ? 0 : 1;
}
