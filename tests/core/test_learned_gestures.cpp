// The learned tracker on rendered hands that do and do not point: it follows an open hand and
// a fist as it follows a pointing hand, but says "pointing" on few of their frames (a hand
// that does not point must not steer the head) and on most of the pointing hand's.
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {

using gc::Gesture;

struct Shares {
    int visible = 0;   // frames with the hand in view
    int on_hand = 0;   // tracked, on the hand
    int pointing = 0;  // of those, reported as pointing
    double tracked() const { return visible ? double(on_hand) / visible : 0.0; }
    double pointed() const { return on_hand ? double(pointing) / on_hand : 0.0; }
};

// The clean room's seeds 1-3 with the mixed motion, 120 frames each, one eye.
Shares run_gesture(Gesture gesture)
{
    Shares s;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        gc::sim::SceneConfig cfg;
        cfg.seed = seed;
        cfg.gesture = gesture;
        const gc::sim::Scene scene(cfg);
        gc::TrackerParams params;
        params.seed = seed;
        gc::HandTracker tracker(params);
        cv::Mat frame;
        gc::sim::EyeTruth truth;
        for (int f = 0; f < 120; ++f) {
            scene.render(f, gc::Eye::Left, {}, frame, &truth);
            const gc::EyeEstimate& e = tracker.process(frame);
            s.visible += truth.visible;
            if (!truth.visible || !e.valid() || (e.bbox & truth.bbox).area() == 0) continue;
            ++s.on_hand;
            s.pointing += e.pointing();
        }
    }
    std::printf("%s: tracked on the hand %.3f of visible frames, pointing %.3f of those\n",
                std::string(to_string(gesture)).c_str(), s.tracked(), s.pointed());
    return s;
}

// The landmark model reads the rendered pointing hand as a fist or "other" on single checks
// now and then; such a reading is not taken unless the next check repeats it (without that,
// 82 % of these frames were reported pointing).
TEST(LearnedGestures, PointingHandIsReportedPointing)
{
    const Shares s = run_gesture(Gesture::Pointing);
    EXPECT_GE(s.tracked(), 0.9);
    EXPECT_GE(s.pointed(), 0.9);
}

TEST(LearnedGestures, OpenHandIsTrackedButNotPointing)
{
    const Shares s = run_gesture(Gesture::Open);
    EXPECT_GE(s.tracked(), 0.9);
    EXPECT_LE(s.pointed(), 0.05);
}

TEST(LearnedGestures, FistIsTrackedButRarelyPointing)
{
    const Shares s = run_gesture(Gesture::Fist);
    EXPECT_GE(s.tracked(), 0.9);
    EXPECT_LE(s.pointed(), 0.25);
}

}  // namespace
