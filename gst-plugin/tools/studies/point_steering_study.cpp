// Not a test: steer=point over the simulated head for minutes of a rendered speaker, in real
// time (the head moves on the wall clock), the tracker's output driving the head link as in
// the element. A talking hand is played by a pointing hand whose direction keeps moving: from
// the first frame (the wave included) it swings about (roll 25 deg at 0.8 Hz and 12 deg at
// 1.7 Hz, yaw 15 deg at 0.55 Hz) while the hand drifts about the view (motion translate).
// A waving hand is an open hand moving the same way; a held pointing keeps one direction
// while the hand drifts the same way.
//
//   point_steering_study talk|wave|held [SECONDS [SEED [tracker|learned|truth [point|fixate]]]]
//   (default 300 s, seed 3, point)
//
// `tracker` tracks with the motion detector (as the closed-loop tests), `learned` with the
// learned detector (the element's default); `truth` hands the link the rendered hand itself (its palm where each view shows it, its
// true 3D pointing) instead of the tracker's estimate: the steering on a perfect tracker.
//
// With `fixate` the head only keeps the hand in view, and the tracker's pointing goes to the
// dwell as the element's output=attended and director take it: each pick is a target they
// would frame (the director moves once per pick).
//
// Prints the looks (commands that turn the head to a target), the returns, the picks, the frames the
// hand was tracked, the longest stretch over which the tracker's ray stayed within the
// dwell's 6 deg, and for each look how far the true target was from the left eye's axis.
#include "headctl/steering/head_link.hpp"
#include "running_head.hpp"
#include "sim/scene.hpp"
#include "stereo/head_geometry.hpp"
#include "stereo/pointing_dwell.hpp"
#include "tracker/pointing_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace gc;
using Clock = std::chrono::steady_clock;

constexpr double kPi = std::numbers::pi;
constexpr double kTargetDistanceMm = 600.0;  // the room's wall is 3 m away: farther targets lie past it
constexpr double kSteadyDeg = 6.0;           // gc::DwellParams::steady_deg

struct Figures {
    int frames = 0, tracked = 0, both_tracked = 0, pointing = 0;
    std::vector<int> pointing_per_minute;
    int first_tracked = -1;
    int looks = 0, returns = 0, follows = 0, pauses = 0;
    int picks = 0;                       // targets the dwell picked (the attended crop's and the director's)
    double longest_steady_s = 0.0;       // the tracker's ray within kSteadyDeg of where the stretch began
    std::vector<double> look_error_deg;  // per look: the true target off the left eye's axis, mid-look
    std::vector<double> back_after_s;    // per return: from the return command to the hand tracked again
};

// The speaker's hand at frame `i`: the scene's script (the wave, then a drift) with, for a
// talking hand, a pointing direction that keeps swinging.
sim::HandPose speaker(const sim::Scene& scene, int i, bool talking)
{
    sim::HandPose p = scene.hand_pose(i);
    if (!talking) return p;
    const double t = i / scene.config().fps;
    p.roll_deg += 25.0 * std::sin(2 * kPi * 0.8 * t) + 12.0 * std::sin(2 * kPi * 1.7 * t + 1.0);
    p.yaw_deg += 15.0 * std::sin(2 * kPi * 0.55 * t + 2.0);
    return p;
}

double angle_deg(const cv::Vec3d& a, const cv::Vec3d& b)
{
    return std::acos(std::clamp(a.dot(b) / (cv::norm(a) * cv::norm(b)), -1.0, 1.0)) * 180.0 / kPi;
}

// Renders one eye; a view past the room's wall shows no hand (grey).
void view(const sim::Scene& scene, const sim::HandPose& hand, int i, Eye eye, const HeadPose& pose, cv::Mat& bgr,
          sim::EyeTruth& truth)
{
    try {
        scene.render_pose(hand, i, eye, pose, bgr, &truth);
    } catch (const std::invalid_argument&) {
        bgr.create(scene.config().height, scene.config().width, CV_8UC3);
        bgr.setTo(cv::Scalar::all(128));
        truth = sim::EyeTruth{};
    }
}

// What a perfect tracker would report: the palm where each view shows it, and the true 3D
// pointing while both views show a pointing hand.
FrameResult perfect_tracker(const sim::Scene& scene, const sim::HandPose& hand, const sim::EyeTruth (&truth)[2],
                            const HeadPose& pose)
{
    FrameResult r;
    r.stereo = true;
    EyeEstimate* eyes[2] = {&r.left, &r.right};
    for (int k = 0; k < 2; ++k) {
        if (!truth[k].visible) continue;
        eyes[k]->state = TrackState::Tracking;
        eyes[k]->mean.x = truth[k].palm_px.x;
        eyes[k]->mean.y = truth[k].palm_px.y;
        eyes[k]->gesture = truth[k].gesture;
    }
    if (!r.left.valid() || !r.right.valid()) return r;
    r.state = TrackState::Tracking;
    const sim::HandTruth h = scene.hand_truth(hand);
    if (!h.points()) return r;
    const RigidTransform to_left = camera_to_head(scene.calibration().head, pose, Eye::Left).inverse();
    r.pointing.valid = true;
    r.pointing.fingertip_head_mm = h.fingertip_mm;
    r.pointing.palm_head_mm = h.palm_mm;
    r.pointing.direction_head = h.direction;
    r.pointing.fingertip_mm = to_left.apply(h.fingertip_mm);
    r.pointing.palm_mm = to_left.apply(h.palm_mm);
    r.pointing.direction = to_left.R * h.direction;
    return r;
}

// What one run counts, fed with each frame and each steering event.
struct Run {
    Run(const sim::Scene& s, bool t, double look) : scene(s), talking(t), look_s(look) {}
    const sim::Scene& scene;
    bool talking;
    double look_s;
    Figures f;
    PointingDwell dwell;                   // as handtracker's pick_target, with its default properties
    std::optional<cv::Vec3d> steady_from;  // the ray's direction where the current steady stretch began
    double steady_start_s = 0.0;
    std::optional<double> returned_at_s;
    std::optional<double> look_middle_s;
    cv::Vec3d true_target;

    void on_event(headctl::SteeringEvent e, double t_s, int i)
    {
        if (e == headctl::SteeringEvent::Look) {
            ++f.looks;
            const sim::HandTruth truth = scene.hand_truth(speaker(scene, i, talking));
            true_target = truth.fingertip_mm + kTargetDistanceMm * truth.direction;
            look_middle_s = t_s + 0.5 + 0.5 * look_s;  // the turn takes < 0.5 s
        }
        if (e == headctl::SteeringEvent::Return) ++f.returns, returned_at_s = t_s;
        if (e == headctl::SteeringEvent::Follow) ++f.follows;
        if (e == headctl::SteeringEvent::ManualPause) ++f.pauses;
    }

    void score(const FrameResult& r, double t_s, int i, const HeadPose& pose)
    {
        ++f.frames;
        if (f.first_tracked < 0 && r.left.valid()) f.first_tracked = i;
        if (r.left.valid()) ++f.tracked;
        if (r.left.valid() && r.right.valid()) ++f.both_tracked;
        const std::size_t minute = static_cast<std::size_t>(t_s / 60.0);
        if (f.pointing_per_minute.size() <= minute) f.pointing_per_minute.resize(minute + 1, 0);
        if (r.left.valid() && returned_at_s) {
            f.back_after_s.push_back(t_s - *returned_at_s);
            returned_at_s.reset();
        }
        if (look_middle_s && t_s >= *look_middle_s) {
            const cv::Vec3d q = camera_to_head(scene.calibration().head, pose, Eye::Left).inverse().apply(true_target);
            f.look_error_deg.push_back(angle_deg(q, {0.0, 0.0, 1.0}));
            look_middle_s.reset();
        }
        DwellParams params;
        params.target.distance_mm = kTargetDistanceMm;
        dwell.update(t_s, r.pointing, params);
        f.picks = dwell.picks();
        if (!r.pointing.valid) return;
        ++f.pointing;
        ++f.pointing_per_minute[minute];
        if (!steady_from || angle_deg(r.pointing.direction_head, *steady_from) > kSteadyDeg) {
            steady_from = r.pointing.direction_head;
            steady_start_s = t_s;
        }
        f.longest_steady_s = std::max(f.longest_steady_s, t_s - steady_start_s);
    }
};

Figures run(bool talking, Gesture gesture, double seconds, std::uint64_t seed, const std::string& source,
            headctl::SteerMode steer)
{
    sim::SceneConfig sc;
    sc.preset = sim::Preset::Light;
    sc.motion = sim::Motion::Translate;
    sc.seed = seed;
    sc.gesture = gesture;
    const sim::Scene scene(sc);
    loopback::RunningHead head(loopback::loopback_head());
    headctl::HeadLinkConfig lc;
    lc.uri = head.uri();
    lc.steer = steer;
    lc.target.distance_mm = kTargetDistanceMm;
    Run* state = nullptr;  // set before the first frame; events come from end_frame
    int frame = 0;
    lc.on_steering = [&](headctl::SteeringEvent e, const std::string& detail) {
        std::printf("  %7.2f s  %s: %s\n", frame / sc.fps, std::string(headctl::to_string(e)).c_str(), detail.c_str());
        state->on_event(e, frame / sc.fps, frame);
    };
    headctl::HeadLink link(lc, scene.calibration());
    TrackerParams params;
    params.particles = 500;
    params.seed = 7;
    // tracker: the motion detector, as the closed-loop tests (the learned key points are less
    // exact on the renderer's rigid hand); learned: the element's default.
    params.detector = source == "learned" ? HandDetector::Learned : HandDetector::Motion;
    const bool truth_only = source == "truth";
    PointingTracker tracker(params, scene.calibration());
    Run run_state(scene, talking, lc.times.look_s);
    state = &run_state;

    const auto start = Clock::now();
    cv::Mat left, right;
    sim::EyeTruth truth[2];
    const int last = static_cast<int>(seconds * sc.fps);
    for (frame = 0; frame < last;) {
        std::this_thread::sleep_until(
            start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(frame / sc.fps)));
        const headctl::HeadAtCapture at = link.begin_frame(link.now());
        const HeadPose pose = at.pose.value_or(HeadPose{});
        const sim::HandPose hand = speaker(scene, frame, talking);
        view(scene, hand, frame, Eye::Left, pose, left, truth[0]);
        view(scene, hand, frame, Eye::Right, pose, right, truth[1]);
        const FrameResult& r = truth_only
                                   ? perfect_tracker(scene, hand, truth, pose)
                                   : tracker.process_stereo(left, right, -1, at.pose, at.left_motion, at.right_motion);
        link.end_frame(r);
        run_state.score(r, frame / sc.fps, frame, pose);
        // Frames the machine could not keep up with are skipped, so the hand keeps its speed.
        const double late = std::chrono::duration<double>(Clock::now() - start).count();
        frame = std::max(frame + 1, static_cast<int>(late * sc.fps));
    }
    return run_state.f;
}

void print(const Figures& f, const char* mode, double seconds)
{
    std::printf("%s, %.0f s: %d frames processed, hand first tracked at frame %d, tracked on %d (%.1f %% of the "
                "frames processed; in both views on %d), a 3D pointing on %d; the tracker's ray stayed within %.0f "
                "deg for at most %.2f s\n",
                mode, seconds, f.frames, f.first_tracked, f.tracked, 100.0 * f.tracked / std::max(f.frames, 1),
                f.both_tracked, f.pointing, kSteadyDeg, f.longest_steady_s);
    std::printf("3D pointings per minute:");
    for (int n : f.pointing_per_minute) std::printf(" %d", n);
    std::printf("\n");
    std::printf("looks (commands turning the head to a target): %d, returns: %d, back to following: %d, manual "
                "pauses: %d\n",
                f.looks, f.returns, f.follows, f.pauses);
    std::printf("picks (targets output=attended and the director would frame): %d\n", f.picks);
    for (std::size_t k = 0; k < f.look_error_deg.size(); ++k)
        std::printf("  look %zu: the true target %.1f deg off the left eye's axis mid-look\n", k + 1,
                    f.look_error_deg[k]);
    for (std::size_t k = 0; k < f.back_after_s.size(); ++k)
        std::printf("  return %zu: hand tracked again %.2f s after the return command\n", k + 1, f.back_after_s[k]);
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode != "talk" && mode != "wave" && mode != "held") {
        std::fprintf(stderr, "usage: point_steering_study talk|wave|held [SECONDS [SEED [tracker|learned|truth "
                             "[point|fixate]]]]\n");
        return 2;
    }
    const double seconds = argc > 2 ? std::atof(argv[2]) : 300.0;
    const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 3;
    const std::string source = argc > 4 ? argv[4] : "tracker";
    const std::string steer = argc > 5 ? argv[5] : "point";
    if (steer != "point" && steer != "fixate") {
        std::fprintf(stderr, "the head steers point or fixate\n");
        return 2;
    }
    if (source != "tracker" && source != "learned" && source != "truth") {
        std::fprintf(stderr, "the hand's source is tracker, learned or truth\n");
        return 2;
    }
    std::printf("%s hand, %s\n", mode.c_str(),
                source == "truth" ? "the rendered truth" : ("the tracker's output, detector " + source).c_str());
    const headctl::SteerMode steer_mode = steer == "point" ? headctl::SteerMode::Point : headctl::SteerMode::Fixate;
    print(run(mode != "held", mode == "wave" ? Gesture::Open : Gesture::Pointing, seconds, seed, source, steer_mode),
          mode.c_str(), seconds);
    return 0;
}
