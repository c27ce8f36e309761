// The whole loop through GStreamer, in real time: two live handscenesrc rendering from the
// simulated head's pose -> handtracker steering that head over loopback TCP -> fakesink.
// The hand must stay in the middle of the left view; a head killed and restarted mid-stream
// must not stop the pipeline, must be reported, and must be back within 2 s; a head moved by
// someone else is left there for manual-pause seconds, with head-steering messages.
#include "gst_fixture.hpp"

#include "running_head.hpp"
#include "headctl/head_client.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace {

using gc::loopback::loopback_head;
using gc::loopback::RunningHead;
using namespace std::chrono_literals;

constexpr int kFps = 30;

std::string loop_pipeline(const std::string& uri, const char* steer, int frames)
{
    const std::string common = " is-live=true scene=light motion=translate seed=3 head=" + uri +
                               " num-buffers=" + std::to_string(frames) + " ";
    return "handscenesrc name=l eye=left" + common +
           "! t.sink_left handscenesrc name=r eye=right truth-messages=false" + common +
           "! t.sink_right handtracker name=t particles=500 seed=7 head=" + uri + " steer=" + steer + " ! fakesink";
}

GstClockTime timestamp_of(const GstStructure* s)
{
    guint64 t = GST_CLOCK_TIME_NONE;
    gst_structure_get_uint64(s, "timestamp", &t);
    return t;
}

struct LoopFigures {
    GstClockTime acquired = GST_CLOCK_TIME_NONE;  // first output with the left eye tracking
    int scored = 0, centred = 0;                  // truth frames from 1 s after acquisition
    int outputs = 0, tracked = 0;                 // output frames from 1 s after acquisition
    double max_pan_deg = 0.0;
    double centred_fraction() const { return scored ? double(centred) / scored : 0.0; }
    double tracked_fraction() const { return outputs ? double(tracked) / outputs : 0.0; }
};

LoopFigures figures(const gc::test::RunResult& r, const char* steer)
{
    LoopFigures f;
    const auto outputs = r.named("hand-pointing", "t");
    for (const GstStructure* m : outputs) {
        const GstStructure* left = gc::test::get_child(m, "left");
        if (left && g_str_equal(gst_structure_get_string(left, "state"), "tracking")) {
            f.acquired = timestamp_of(m);
            break;
        }
    }
    if (!GST_CLOCK_TIME_IS_VALID(f.acquired)) return f;
    const GstClockTime from = f.acquired + GST_SECOND;
    for (const GstStructure* m : outputs) {
        if (timestamp_of(m) < from) continue;
        ++f.outputs;
        const GstStructure* left = gc::test::get_child(m, "left");
        f.tracked += left && g_str_equal(gst_structure_get_string(left, "state"), "tracking");
    }
    for (const GstStructure* t : r.named("hand-truth", "l")) {
        f.max_pan_deg = std::max(f.max_pan_deg, std::abs(gc::test::get_double(t, "head-pan-deg")));
        if (timestamp_of(t) < from) continue;
        ++f.scored;
        gboolean visible = FALSE;
        gst_structure_get_boolean(t, "visible", &visible);
        const double x = gc::test::get_double(t, "palm-x"), y = gc::test::get_double(t, "palm-y");
        f.centred += visible && std::abs(x - 320.0) < 640.0 / 6 && std::abs(y - 240.0) < 480.0 / 6;
    }
    std::printf("steer=%s: acquired at %.2f s; from 1 s later: hand in the central third of the left view in "
                "%.1f %% of %d frames, left eye tracking in %.1f %% of %d outputs, largest pan %.1f deg\n",
                steer, double(f.acquired) / GST_SECOND, 100.0 * f.centred_fraction(), f.scored,
                100.0 * f.tracked_fraction(), f.outputs, f.max_pan_deg);
    return f;
}

TEST(HeadLoop, FixateKeepsTheHandInTheMiddleAndTracksAsWellAsStaticCameras)
{
    gc::test::init_gstreamer();
    LoopFigures off, fixate;
    for (const char* steer : {"off", "fixate"}) {
        RunningHead head(loopback_head(0, 0.02));
        const gc::test::RunResult r = gc::test::run_pipeline(loop_pipeline(head.uri(), steer, 10 * kFps));
        ASSERT_TRUE(r.eos) << r.error;
        (g_str_equal(steer, "off") ? off : fixate) = figures(r, steer);
    }
    ASSERT_TRUE(GST_CLOCK_TIME_IS_VALID(fixate.acquired)) << "never acquired";
    ASSERT_GT(fixate.scored, 150);
    EXPECT_GE(fixate.centred_fraction(), 0.95);
    EXPECT_GT(fixate.max_pan_deg, 3.0);  // the head did follow
    EXPECT_EQ(off.max_pan_deg, 0.0);
    EXPECT_LT(off.centred_fraction(), 0.9);  // without steering the same motion leaves the middle
    EXPECT_GE(fixate.tracked_fraction(), off.tracked_fraction() - 0.01);
}

TEST(HeadLoop, AHeadRestartedMidStreamIsBackWithinTwoSeconds)
{
    gc::test::init_gstreamer();
    auto head = std::make_unique<RunningHead>(loopback_head(0, 0.02));
    const std::uint16_t port = head->port();
    const std::string uri = head->uri();
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(loop_pipeline(uri, "fixate", 8 * kFps));
    ASSERT_TRUE(pipeline);

    // Kill the head 2.5 s after PLAYING and start a new one on the same port 1 s later.
    const auto start = std::chrono::steady_clock::now();
    double killed_s = 0.0, restarted_s = 0.0;
    std::thread operator_thread([&] {
        std::this_thread::sleep_until(start + 2500ms);
        head.reset();
        killed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::this_thread::sleep_until(start + 3500ms);
        head = std::make_unique<RunningHead>(loopback_head(port, 0.02));
        restarted_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get());
    operator_thread.join();
    ASSERT_TRUE(r.eos) << r.error;

    // Every frame came out, with no stall while the head was away.
    const auto outputs = r.named("hand-pointing", "t");
    EXPECT_GE(outputs.size(), size_t(8 * kFps - 2));
    double largest_gap_s = 0.0, previous_s = -1.0;
    for (size_t i = 0; i < r.messages.size(); ++i) {
        if (r.sources[i] != "t" || !gst_structure_has_name(r.messages[i].get(), "hand-pointing")) continue;
        if (previous_s >= 0.0) largest_gap_s = std::max(largest_gap_s, r.received_s[i] - previous_s);
        previous_s = r.received_s[i];
    }
    EXPECT_LT(largest_gap_s, 0.5);

    // One warning from the tracker for the outage, naming the head, after the kill. The only
    // other warning allowed is the one a machine too busy for 30 stereo frames/s gives
    // (views reaching the tracker late), which is about the machine, not the head.
    int outage_warnings = 0;
    for (size_t i = 0; i < r.warnings.size(); ++i) {
        if (r.warnings[i].rfind("t: ", 0) != 0) continue;
        if (r.warnings[i].find("after capture") != std::string::npos) {
            std::printf("busy machine: %s\n", r.warnings[i].c_str());
            continue;
        }
        ++outage_warnings;
        EXPECT_NE(r.warnings[i].find(uri), std::string::npos) << r.warnings[i];
        EXPECT_GE(r.warnings_s[i], killed_s - 0.1);
    }
    EXPECT_EQ(outage_warnings, 1);

    // Connected again: the tracker's head-connection messages after the restart.
    std::optional<double> back_s;
    for (size_t i = 0; i < r.messages.size(); ++i)
        if (r.sources[i] == "t" && gst_structure_has_name(r.messages[i].get(), "head-connection") &&
            g_str_equal(gst_structure_get_string(r.messages[i].get(), "state"), "connected") &&
            r.received_s[i] > restarted_s && !back_s)
            back_s = r.received_s[i];
    ASSERT_TRUE(back_s.has_value()) << "never reconnected";
    std::printf("head killed at %.2f s, restarted at %.2f s, handtracker reconnected %.0f ms later; largest gap "
                "between output frames %.0f ms; %zu outputs\n",
                killed_s, restarted_s, 1000.0 * (*back_s - restarted_s), 1000.0 * largest_gap_s, outputs.size());
    EXPECT_LT(*back_s - restarted_s, 2.0);
}

TEST(HeadLoop, AManualMoveIsLeftAloneForManualPauseAndReported)
{
    // The hand holds still; the element keeps it in view with the head at rest. Once the
    // head has rested for half a second and 15 frames (looked for from the stream's 3rd
    // second until its 9th, counted in frames that passed the element, so that a slow start
    // under load cannot put the move before the element has seen the head), someone moves
    // it with another client (as `headctl move pan=15` does). A move made while the element
    // itself turns the head is overridden by its next command (docs/steering.md), so the
    // test waits for rest. The motion detector's contour holds a still hand steadier than
    // the learned key points, whose frame-to-frame jitter can take the offset past the
    // release band and twitch the head.
    gc::test::init_gstreamer();
    RunningHead head(loopback_head(0, 0.02));
    const std::string common = " is-live=true scene=light motion=static seed=3 head=" + head.uri() +
                               " num-buffers=" + std::to_string(12 * kFps) + " ";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "handscenesrc name=l eye=left" + common + "! t.sink_left handscenesrc name=r eye=right truth-messages=false" +
        common + "! t.sink_right handtracker name=t particles=500 seed=7 head=" + head.uri() +
        " steer=fixate detector=motion manual-pause=1.5 message-updates=none ! fakesink name=out");
    ASSERT_TRUE(pipeline);
    std::atomic<int> frames{0};
    gc::test::probe_buffers(
        pipeline.get(), "out", "sink",
        [](GstPad*, GstPadProbeInfo*, gpointer count) {
            ++*static_cast<std::atomic<int>*>(count);  // a frame the element has finished
            return GST_PAD_PROBE_OK;
        },
        &frames);
    gc::headctl::HeadClientConfig driver_config;
    driver_config.uri = head.uri();
    gc::headctl::HeadClient driver(driver_config);
    std::atomic<bool> done{false};
    bool moved = false;
    int moved_at_frame = 0;
    std::thread mover([&] {
        while (!done && frames < 3 * kFps) std::this_thread::sleep_for(20ms);
        for (int resting = 0, rest_from = frames; !done && frames < 9 * kFps;) {
            std::this_thread::sleep_for(20ms);
            const gc::headctl::HeadState s = head.state();
            const bool still = std::none_of(s.moving.begin(), s.moving.end(), [](bool m) { return m; });
            if (!still || resting == 0) rest_from = frames;
            resting = still ? resting + 1 : 0;
            if (resting >= 25 && frames - rest_from >= 15) break;
        }
        if (done || frames >= 9 * kFps) return;
        gc::headctl::HeadCommand turn{gc::headctl::CommandKind::Absolute, {}};
        turn.values.set(gc::headctl::Axis::Pan, 15.0);
        driver.submit(turn);
        moved_at_frame = frames;
        // The element must not cancel a move it sees starting (it turned the head back when
        // the picture shifted before the first samples' 0.1-0.4 deg were taken for a move).
        moved = gc::loopback::eventually([&] { return head.state().pose.pan_deg > 10.0; }, 2000ms);
    });
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get());
    done = true;
    mover.join();
    ASSERT_TRUE(r.eos) << r.error;
    ASSERT_GT(moved_at_frame, 0) << "the element never held the head still for half a second";
    EXPECT_TRUE(moved) << "the move did not reach pan 10 deg; the other client: '" << driver.last_error() << "'";
    std::vector<std::string> events;
    for (size_t i = 0; i < r.messages.size(); ++i)
        if (r.sources[i] == "t" && gst_structure_has_name(r.messages[i].get(), "head-steering")) {
            events.emplace_back(gst_structure_get_string(r.messages[i].get(), "event"));
            std::printf("%.2f s: %s: %s\n", r.received_s[i], events.back().c_str(),
                        gst_structure_get_string(r.messages[i].get(), "detail"));
        }
    std::printf("moved to pan 15 deg after %d frames had passed the element\n", moved_at_frame);
    for (size_t i = 0; i < r.warnings.size(); ++i)
        std::printf("%.2f s: warning: %s\n", r.warnings_s[i], r.warnings[i].c_str());
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0], "manual-pause");
    EXPECT_EQ(events[1], "resume");
    // The move stayed: the views were rendered from the head at 15 deg (before, the
    // element's next command stopped the head within a frame of the move).
    double largest_pan = 0.0;
    for (const GstStructure* t : r.named("hand-truth", "l"))
        largest_pan = std::max(largest_pan, gc::test::get_double(t, "head-pan-deg"));
    EXPECT_GT(largest_pan, 14.5) << "the element undid the move";
}

TEST(HeadLoop, AHeadTurnedPastTheSimulatedRoomDoesNotStopTheScene)
{
    // headsim pans to 120 deg; the simulated room (one wall ahead) cannot be seen from there.
    // handscenesrc follows the head as far as the room reaches, then keeps that view with
    // one warning, and the stream runs to its end.
    gc::test::init_gstreamer();
    RunningHead head(loopback_head(0, 0.0));
    gc::headctl::HeadClientConfig driver_config;
    driver_config.uri = head.uri();
    gc::headctl::HeadClient driver(driver_config);
    std::thread mover([&] {
        std::this_thread::sleep_for(300ms);
        gc::headctl::HeadCommand turn{gc::headctl::CommandKind::Absolute, {}};
        turn.values.set(gc::headctl::Axis::Pan, 120.0);
        driver.submit(turn);
    });
    const gc::test::RunResult r = gc::test::run_pipeline(
        "handscenesrc name=l is-live=true scene=light head=" + head.uri() + " num-buffers=75 ! fakesink");
    mover.join();
    ASSERT_TRUE(r.eos) << r.error;
    const auto truths = r.named("hand-truth", "l");
    EXPECT_EQ(truths.size(), 75u);
    double largest_pan = 0.0;
    for (const GstStructure* t : truths) largest_pan = std::max(largest_pan, gc::test::get_double(t, "head-pan-deg"));
    EXPECT_GT(largest_pan, 20.0);  // it did follow the head
    EXPECT_LT(largest_pan, 90.0);  // but only as far as the room can be shown
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("simulated room"), std::string::npos) << r.warnings[0];
}

TEST(HeadLoop, AZoomingHeadNarrowsTheRenderedView)
{
    // headsim at 2x: handscenesrc renders at twice the focal length, so the still hand's
    // palm-to-fingertip span in the image is twice that of a fixed rig and the truth names
    // the zoom.
    gc::test::init_gstreamer();
    const char* scene = "handscenesrc name=l scene=clean motion=static num-buffers=3 ";
    const gc::test::RunResult wide = gc::test::run_pipeline(std::string(scene) + "! fakesink");
    ASSERT_TRUE(wide.eos) << wide.error;

    RunningHead head(loopback_head(0, 0.0));
    gc::headctl::HeadClientConfig driver_config;
    driver_config.uri = head.uri();
    gc::headctl::HeadClient driver(driver_config);
    gc::headctl::HeadCommand zoom{gc::headctl::CommandKind::Absolute, {}};
    zoom.values.set(gc::headctl::Axis::Zoom, 2.0);
    driver.submit(zoom);
    const auto zoomed = [&] {
        const auto s = driver.latest();
        return s && s->state.pose.zoom == 2.0 && !s->state.moving_axis(gc::headctl::Axis::Zoom);
    };
    for (int i = 0; i < 500 && !zoomed(); ++i) std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(zoomed());
    const gc::test::RunResult narrow =
        gc::test::run_pipeline(std::string(scene) + "is-live=true head=" + head.uri() + " ! fakesink");
    ASSERT_TRUE(narrow.eos) << narrow.error;

    const auto span = [](const GstStructure* t) {
        return std::hypot(gc::test::get_double(t, "fingertip-x") - gc::test::get_double(t, "palm-x"),
                          gc::test::get_double(t, "fingertip-y") - gc::test::get_double(t, "palm-y"));
    };
    const auto a = wide.named("hand-truth", "l"), b = narrow.named("hand-truth", "l");
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    EXPECT_DOUBLE_EQ(gc::test::get_double(a.back(), "head-zoom"), 1.0);
    EXPECT_DOUBLE_EQ(gc::test::get_double(b.back(), "head-zoom"), 2.0);
    EXPECT_NEAR(span(b.back()) / span(a.back()), 2.0, 0.02);
}

}  // namespace
