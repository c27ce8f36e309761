// When the hand is lost, fixate mode holds the head still, widens the view after `widen-after`
// seconds and goes home after `home-after`; when the hand is back it steers again. This study
// times each step against its setting, over TCP against the simulated head in real time: the
// head link is fed 30 frames a second (the hand tracked right of centre, then lost, then back),
// and a watcher reads the head's state every 2 ms on the server's side.
//
//     build/gst-plugin/tools/studies/loss_timing [EPISODES [WIDEN_AFTER_S [HOME_AFTER_S]]]
//
// It prints, per episode, the delays from the first lost frame to the widening command, to the
// head's zoom starting to fall, to the home command and to the head starting home, and from the
// first tracked frame after the loss to the head turning towards the hand again; then the
// median and the largest deviation of each from its setting.
#include "headctl/steering/head_link.hpp"
#include "running_head.hpp"
#include "stereo/calibration.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace gc {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double seconds_between(Clock::time_point from, Clock::time_point to)
{
    return std::chrono::duration<double>(to - from).count();
}

// The head's pose sampled every 2 ms on the server's side, with the wall time of each sample.
class HeadWatch {
public:
    explicit HeadWatch(headctl::HeadServer& server) : server_(server), thread_([this] { watch(); }) {}
    ~HeadWatch()
    {
        stop_ = true;
        thread_.join();
    }
    // The first time at or after `from` when `moved(pose)` holds; nullopt if never.
    template <class Predicate>
    std::optional<Clock::time_point> first(Clock::time_point from, Predicate moved) const
    {
        const std::lock_guard lock(mutex_);
        for (const auto& [t, pose] : samples_)
            if (t >= from && moved(pose)) return t;
        return std::nullopt;
    }
    HeadPose at(Clock::time_point t) const
    {
        const std::lock_guard lock(mutex_);
        HeadPose last;
        for (const auto& [when, pose] : samples_) {
            if (when > t) break;
            last = pose;
        }
        return last;
    }

private:
    void watch()
    {
        while (!stop_) {
            server_.with_model([this](headctl::HeadModel& m, double now_s) {
                const HeadPose pose = m.state(now_s).pose;
                const std::lock_guard lock(mutex_);
                samples_.emplace_back(Clock::now(), pose);
            });
            std::this_thread::sleep_for(2ms);
        }
    }
    headctl::HeadServer& server_;
    mutable std::mutex mutex_;
    std::vector<std::pair<Clock::time_point, HeadPose>> samples_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

const StereoCalibration& calibration()
{
    static const StereoCalibration c = default_calibration({640, 480});
    return c;
}

// The hand sits still at this pan in the room (degrees, right of the head's home).
constexpr double kHandPanDeg = 20.0;

// The left eye tracks the hand `pan_deg` right of the image centre.
FrameResult hand_right_of_centre(double pan_deg)
{
    FrameResult r;
    r.stereo = true;
    r.state = TrackState::Tracking;
    r.left.state = TrackState::Tracking;
    r.left.mean.x = calibration().M1(0, 2) + calibration().M1(0, 0) * std::tan(pan_deg * std::numbers::pi / 180.0);
    r.left.mean.y = calibration().M1(1, 2);
    r.right = r.left;
    return r;
}

// The frame of a head at `at`: the still hand where it shows from that pose.
FrameResult hand_in_view(const headctl::HeadAtCapture& at)
{
    return hand_right_of_centre(kHandPanDeg - (at.pose ? at.pose->pan_deg : 0.0));
}

FrameResult hand_lost(const headctl::HeadAtCapture&) { return FrameResult{}; }

// Feeds the link 30 frames a second for `duration`; returns the time of the first frame.
template <class Frame>
Clock::time_point run_frames(headctl::HeadLink& link, Clock::duration duration, Frame frame)
{
    const Clock::time_point start = Clock::now();
    for (auto next = start; Clock::now() < start + duration; next += 33333us) {
        link.end_frame(frame(link.begin_frame(link.now())));
        std::this_thread::sleep_until(next + 33333us);
    }
    return start;
}

struct Episode {
    double widen_command_s = NAN, widen_head_s = NAN, home_command_s = NAN, home_head_s = NAN, resume_head_s = NAN;
};

// One loss: the still hand tracked for 1.5 s (the head turns to it), lost until
// `home_after_s` + 1 s (the head holds, widens, goes home), then found again.
Episode one_loss(headctl::HeadLink& link, const HeadWatch& watch, const std::vector<std::pair<Clock::time_point,
                 headctl::HeadCommand>>& commands, std::mutex& commands_mutex, double home_after_s)
{
    run_frames(link, 1500ms, hand_in_view);
    const auto lost = run_frames(link, std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(home_after_s + 1.0)),
                                 hand_lost);
    const HeadPose at_loss = watch.at(lost);
    Episode e;
    {
        const std::lock_guard lock(commands_mutex);
        for (const auto& [t, c] : commands) {
            if (t < lost) continue;
            if (std::isnan(e.widen_command_s) && c.kind == headctl::CommandKind::Velocity &&
                c.values[headctl::Axis::Zoom].value_or(0.0) < 0.0)
                e.widen_command_s = seconds_between(lost, t);
            if (std::isnan(e.home_command_s) && c.kind == headctl::CommandKind::Home)
                e.home_command_s = seconds_between(lost, t);
        }
    }
    if (const auto t = watch.first(lost, [&](const HeadPose& p) { return p.zoom < at_loss.zoom - 0.01; }))
        e.widen_head_s = seconds_between(lost, *t);
    const Clock::time_point home_sent =
        lost + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(e.home_command_s));
    const HeadPose at_home = watch.at(home_sent);
    if (const auto t = watch.first(home_sent, [&](const HeadPose& p) { return p.pan_deg < at_home.pan_deg - 0.1; }))
        e.home_head_s = seconds_between(lost, *t);
    const auto found = run_frames(link, 1500ms, hand_in_view);
    const HeadPose at_found = watch.at(found);
    if (const auto t = watch.first(found, [&](const HeadPose& p) { return p.pan_deg > at_found.pan_deg + 0.1; }))
        e.resume_head_s = seconds_between(found, *t);
    return e;
}

void print_summary(const char* what, std::vector<double> values, double setting)
{
    std::erase_if(values, [](double v) { return std::isnan(v); });
    if (values.empty()) {
        std::printf("%-34s never\n", what);
        return;
    }
    std::sort(values.begin(), values.end());
    double worst = 0.0;
    for (double v : values) worst = std::max(worst, std::abs(v - setting));
    std::printf("%-34s setting %5.2f s  median %6.3f s  range %6.3f..%6.3f s  largest deviation %4.0f ms (%zu)\n",
                what, setting, values[values.size() / 2], values.front(), values.back(), worst * 1000.0, values.size());
}

// Zooms the head to 6x through a client of its own, as `headctl move zoom=6` would: a narrow
// view to widen from (going home sets the zoom back to 1x).
bool narrow_view(const std::string& uri)
{
    headctl::HeadClientConfig cc;
    cc.uri = uri;
    headctl::HeadClient driver(cc);
    headctl::HeadCommand zoom{headctl::CommandKind::Absolute, {}};
    zoom.values.set(headctl::Axis::Zoom, 6.0);
    driver.submit(zoom);
    return loopback::eventually([&] { return driver.latest() && driver.latest()->state.pose.zoom == 6.0; }, 5000ms);
}

int run(int episodes, double widen_after_s, double home_after_s)
{
    loopback::RunningHead head(loopback::loopback_head());
    HeadWatch watch(head.server());
    std::mutex commands_mutex;
    std::vector<std::pair<Clock::time_point, headctl::HeadCommand>> commands;
    headctl::HeadLinkConfig lc;
    lc.uri = head.uri();
    lc.steer = headctl::SteerMode::Fixate;
    lc.fixate.widen_after_s = widen_after_s;
    lc.fixate.hold_s = home_after_s;
    lc.on_command = [&](const headctl::HeadCommand& c) {
        const std::lock_guard lock(commands_mutex);
        commands.emplace_back(Clock::now(), c);
    };
    headctl::HeadLink link(lc, calibration());
    if (!loopback::eventually([&] { return link.client().limits().has_value(); }, 5000ms)) {
        std::fprintf(stderr, "loss_timing: the simulated head did not answer\n");
        return 1;
    }
    std::vector<Episode> all;
    std::printf("episode  widen cmd  zoom falls  home cmd  head homes  (s after the loss)  turns to the hand (s after found)\n");
    for (int i = 0; i < episodes; ++i) {
        if (!narrow_view(head.uri())) {
            std::fprintf(stderr, "loss_timing: the head did not zoom in\n");
            return 1;
        }
        const Episode e = one_loss(link, watch, commands, commands_mutex, home_after_s);
        std::printf("%7d  %9.3f  %10.3f  %8.3f  %10.3f  %37.3f\n", i + 1, e.widen_command_s, e.widen_head_s,
                    e.home_command_s, e.home_head_s, e.resume_head_s);
        all.push_back(e);
    }
    auto column = [&](double Episode::*field) {
        std::vector<double> v;
        for (const Episode& e : all) v.push_back(e.*field);
        return v;
    };
    print_summary("widen command after the loss", column(&Episode::widen_command_s), widen_after_s);
    print_summary("zoom starts to fall", column(&Episode::widen_head_s), widen_after_s);
    print_summary("home command after the loss", column(&Episode::home_command_s), home_after_s);
    print_summary("head starts home", column(&Episode::home_head_s), home_after_s);
    print_summary("head turns to the found hand", column(&Episode::resume_head_s), 0.0);
    return 0;
}

}  // namespace
}  // namespace gc

int main(int argc, char** argv)
{
    const int episodes = argc > 1 ? std::atoi(argv[1]) : 10;
    const double widen_after_s = argc > 2 ? std::atof(argv[2]) : 1.0;
    const double home_after_s = argc > 3 ? std::atof(argv[3]) : 3.0;
    if (episodes < 1 || widen_after_s <= 0.0 || home_after_s <= widen_after_s) {
        std::fprintf(stderr, "usage: loss_timing [EPISODES [WIDEN_AFTER_S [HOME_AFTER_S]]] (0 < widen-after < home-after)\n");
        return 2;
    }
    return gc::run(episodes, widen_after_s, home_after_s);
}
