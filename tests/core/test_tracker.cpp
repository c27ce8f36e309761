#include "face_crossing.hpp"
#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"
#include "tracker/stereo_tracker.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

gc::sim::SceneConfig mixed_scene(gc::sim::Preset preset, std::uint64_t seed)
{
    gc::sim::SceneConfig cfg;
    cfg.preset = preset;
    cfg.motion = gc::sim::Motion::Mixed;
    cfg.seed = seed;
    return cfg;
}

// These tests hold the thesis's tracker to its figures: detection by motion and skin,
// nothing learned (the learned detector has its own tests in test_learned_tracker.cpp).
gc::TrackerParams thesis_params()
{
    gc::TrackerParams params;
    params.detector = gc::HandDetector::Motion;
    return params;
}

gc::TrackerParams seeded_params(int particles, std::uint64_t seed)
{
    gc::TrackerParams params = thesis_params();
    params.particles = particles;
    params.seed = seed;
    return params;
}

// A drawn pointing hand (palm disc, index finger, thumb) over a background with non-skin
// clutter and a few small skin-coloured patches, with sensor noise from OpenCV's RNG.
struct DrawnScene {
    cv::Mat3b background;
    cv::Vec3b skin{105, 140, 205};  // BGR

    explicit DrawnScene(std::uint32_t seed, cv::Size size = {320, 240}) : background(size)
    {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> c(30, 220), px(0, size.width - 1), py(0, size.height - 1), sz(8, 50);
        background.setTo(cv::Vec3b(60, 70, 65));
        for (int i = 0; i < 40; ++i)
            cv::rectangle(background, cv::Rect(px(rng), py(rng), sz(rng), sz(rng)),
                          cv::Scalar(c(rng), c(rng), c(rng) / 3), cv::FILLED);
        for (int i = 0; i < 4; ++i)  // small skin-coloured clutter
            cv::circle(background, {px(rng), py(rng)}, 4, cv::Scalar(skin), cv::FILLED);
    }

    void render(cv::Point2d palm, double finger_deg, double s, cv::Mat3b& out, cv::Mat1b& mask) const
    {
        mask = cv::Mat1b(background.size(), uchar(0));
        cv::circle(mask, palm, cvRound(22 * s), 255, cv::FILLED);
        const double a = finger_deg * std::numbers::pi / 180.0;
        const cv::Point2d dir(std::cos(a), -std::sin(a)), side(-dir.y, dir.x);
        const cv::Point2d base = palm + dir * (15.0 * s), tip = palm + dir * (62.0 * s);
        std::vector<cv::Point> finger{base + side * (5.0 * s), tip + side * (5.0 * s), tip - side * (5.0 * s),
                                      base - side * (5.0 * s)};
        cv::fillConvexPoly(mask, finger, 255);
        cv::circle(mask, tip, cvRound(5 * s), 255, cv::FILLED);
        cv::circle(mask, palm + side * (26.0 * s) + dir * (6.0 * s), cvRound(7 * s), 255, cv::FILLED);
        paint(mask, out);
    }

    // The background with skin where `mask` is, plus sensor noise.
    void paint(const cv::Mat1b& mask, cv::Mat3b& out) const
    {
        background.copyTo(out);
        out.setTo(skin, mask);
        cv::Mat3s o;
        out.convertTo(o, CV_16SC3);
        cv::Mat3s n(o.size());
        cv::randn(n, cv::Scalar::all(0), cv::Scalar::all(2.0));
        o += n;
        o.convertTo(out, CV_8UC3);
    }
};

struct Pose {
    cv::Point2d palm;
    double deg;
    double scale;
};

// Waves for 8 frames, then moves, turns and scales smoothly.
Pose scripted(int f)
{
    if (f < 8) return {{150.0 + (f % 2 ? 6.0 : -6.0), 130.0}, 30.0, 1.0};
    const double t = (f - 8) / 30.0;
    return {{150.0 + 40.0 * std::sin(1.3 * t), 130.0 + 25.0 * std::sin(0.9 * t)},
            30.0 + 25.0 * std::sin(1.1 * t),
            1.0 + 0.12 * std::sin(0.7 * t)};
}

double iou(const std::vector<cv::Point2f>& contour, const cv::Mat1b& truth)
{
    cv::Mat1b filled(truth.size(), uchar(0));
    std::vector<cv::Point> poly;
    for (const auto& p : contour) poly.emplace_back(cvRound(p.x), cvRound(p.y));
    cv::fillPoly(filled, std::vector<std::vector<cv::Point>>{poly}, 255);
    cv::Mat1b i, u;
    cv::bitwise_and(filled, truth, i);
    cv::bitwise_or(filled, truth, u);
    return double(cv::countNonZero(i)) / std::max(1, cv::countNonZero(u));
}

TEST(HandTracker, AcquiresAndFollowsAMovingHand)
{
    cv::setRNGSeed(7);
    DrawnScene scene(9);
    gc::TrackerParams params = thesis_params();
    params.particles = 500;
    gc::HandTracker tracker(params);
    cv::Mat3b frame;
    cv::Mat1b truth;
    int tracked = 0, frames = 0;
    double worst = 1.0, sum = 0.0;
    for (int f = 0; f < 100; ++f) {
        const Pose p = scripted(f);
        scene.render(p.palm, p.deg, p.scale, frame, truth);
        const auto& e = tracker.process(frame);
        if (f < 8) continue;
        ++frames;
        if (!e.valid()) continue;
        ++tracked;
        const double v = iou(e.contour, truth);
        worst = std::min(worst, v);
        sum += v;
        EXPECT_NEAR(e.pointing_deg, p.deg, 8.0) << "frame " << f;
        EXPECT_GT(e.confidence, 0.0);
        EXPECT_EQ(e.bbox, cv::boundingRect(e.contour));
    }
    EXPECT_EQ(tracked, frames) << "acquired during the wave and never lost";
    EXPECT_GT(sum / std::max(tracked, 1), 0.9);
    EXPECT_GT(worst, 0.8);
    EXPECT_EQ(tracker.particles().size(), 500u);
}

// A 120-frame clean `mixed` sequence, left eye, 300 particles, as `input` delivers it.
// `check(frame, estimate, truth)`, if given, sees every tracked frame.
struct CleanInput {
    double noise_sigma = 2.0;  // sensor noise, grey levels per channel (the scenes' own)
    int jpeg_quality = 0;      // > 0: every frame passed through JPEG at this quality
};
struct CleanRun {
    int first = -1;           // the first tracked frame
    int tracked = 0;          // tracked frames
    int on_hand_from_30 = 0;  // tracked frames from frame 30 at IoU >= 0.8
    double worst = 1.0;       // the lowest IoU of a tracked frame
    double snr_db = 0.0;
};
constexpr int kCleanRunFrames = 120, kSettledFrame = 30;
using FrameCheck = std::function<void(int, const gc::EyeEstimate&, const gc::sim::EyeTruth&)>;

CleanRun track_clean(std::uint64_t seed, const CleanInput& input = {}, const FrameCheck& check = {})
{
    gc::sim::SceneConfig cfg = mixed_scene(gc::sim::Preset::Clean, seed);
    cfg.noise_sigma = input.noise_sigma;
    const gc::sim::Scene scene(cfg);
    gc::HandTracker tracker(seeded_params(300, seed));
    cv::Mat bgr;
    gc::sim::EyeTruth truth;
    std::vector<uchar> encoded;
    gc::SnrAccumulator snr;
    CleanRun run;
    for (int f = 0; f < kCleanRunFrames; ++f) {
        scene.render(f, gc::Eye::Left, {}, bgr, &truth);
        if (input.jpeg_quality > 0) {
            const std::vector<int> quality{cv::IMWRITE_JPEG_QUALITY, input.jpeg_quality};
            EXPECT_TRUE(cv::imencode(".jpg", bgr, encoded, quality));
            bgr = cv::imdecode(encoded, cv::IMREAD_COLOR);
        }
        const auto& e = tracker.process(bgr);
        const cv::Mat1b tracked = e.valid() ? gc::contour_mask(e.contour, bgr.size()) : cv::Mat1b(bgr.size(), uchar(0));
        snr.add(truth.mask, tracked);
        if (!e.valid()) continue;
        if (run.first < 0) run.first = f;
        ++run.tracked;
        const double iou_f = gc::mask_iou(truth.mask, tracked);
        run.worst = std::min(run.worst, iou_f);
        run.on_hand_from_30 += f >= kSettledFrame && iou_f >= 0.8;
        if (check) check(f, e, truth);
    }
    run.snr_db = snr.snr_db();
    return run;
}

TEST(HandTracker, FollowsARenderedSceneAcrossSeeds)
{
    for (std::uint64_t seed : {1u, 2u}) {
        const auto pointing = [&](int f, const gc::EyeEstimate& e, const gc::sim::EyeTruth& truth) {
            EXPECT_NEAR(e.pointing_deg, truth.pointing_deg, 10.0) << "seed " << seed << " frame " << f;
        };
        const CleanRun run = track_clean(seed, {}, pointing);
        EXPECT_GE(run.first, 0) << "seed " << seed;
        EXPECT_LE(run.first, 10) << "acquired during the wave, seed " << seed;
        EXPECT_GT(run.worst, 0.8) << "seed " << seed;
        EXPECT_GT(run.snr_db, 13.0) << "seed " << seed;
    }
}

// The frames as an MJPEG camera or a lossy recording delivers them: JPEG at quality 80,
// chroma 4:2:0. Quantised chroma leaves holes of non-skin in the hand's membership map and
// shifts its edges (docs/adr/0019); the tracker must still acquire the hand, keep it, and
// outline it well once settled. The SNR bound is a dB below the uncompressed one: on seed 2
// the first template is twisted at the finger until a clean capture replaces it.
TEST(HandTracker, FollowsAJpegCompressedScene)
{
    for (std::uint64_t seed : {1u, 2u}) {
        const CleanRun run = track_clean(seed, {.jpeg_quality = 80});
        ASSERT_GE(run.first, 0) << "seed " << seed;
        EXPECT_LE(run.first, 10) << "acquired during the wave, seed " << seed;
        EXPECT_GE(run.tracked, 0.95 * (kCleanRunFrames - run.first)) << "seed " << seed;
        EXPECT_GE(run.on_hand_from_30, 0.95 * (kCleanRunFrames - kSettledFrame)) << "seed " << seed;
        EXPECT_GT(run.snr_db, 12.0) << "seed " << seed;
    }
}

// A sensor four times noisier than the scenes' own (8 grey levels per channel): at a fixed
// difference threshold much of a still frame would count as moving and acquisition would
// take the wrong thing; the threshold follows the noise instead (docs/adr/0019).
TEST(HandTracker, FollowsTheHandThroughHeavySensorNoise)
{
    for (std::uint64_t seed : {1u, 2u}) {
        const CleanRun run = track_clean(seed, {.noise_sigma = 8.0});
        ASSERT_GE(run.first, 0) << "seed " << seed;
        EXPECT_LE(run.first, 10) << "acquired during the wave, seed " << seed;
        EXPECT_GE(run.on_hand_from_30, 0.95 * (kCleanRunFrames - kSettledFrame)) << "seed " << seed;
        EXPECT_GT(run.snr_db, 11.0) << "seed " << seed;
    }
}

// One eye of a 200-frame face_pass sequence tracked with 1000 particles: the frames where
// the hand crosses the face, and those of them where the tracker was lost or off the hand.
struct FaceCrossing {
    int frames = 0, off = 0;
};

FaceCrossing track_face_pass(std::uint64_t seed, gc::Eye eye)
{
    const gc::sim::Scene scene(mixed_scene(gc::sim::Preset::FacePass, seed));
    gc::HandTracker tracker(seeded_params(1000, seed));
    cv::Mat bgr;
    gc::sim::EyeTruth truth;
    FaceCrossing c;
    for (int f = 0; f < 200; ++f) {
        scene.render(f, eye, {}, bgr, &truth);
        const auto& e = tracker.process(bgr);
        if (!gc_test::hand_crosses_face(truth)) continue;
        ++c.frames;
        c.off += !gc_test::on_the_hand(e, truth, gc::contour_mask(e.contour, bgr.size()));
    }
    return c;
}

// face_pass: the hand passes in front of a face of its own skin colour, where its edges
// vanish. On every frame where the hand covers the face (>= 5 % of the hand over the face's
// skin) the tracker must stay on the hand (tracking, IoU >= 0.5): the thesis lost it there.
// Each seed holds a way to lose it (docs/adr/): on 10, 17, 30 and 73 the hand's own rim is
// cut by the creases of the curled fingers, or a capture during the crossing could merge
// the face (0005, 0007); 22 and 96 hold the hand over the face with few skin edges left
// (0008); on 75 the first template merges two boxes of the hand's colour that stay behind
// as the hand moves off (0009); on 44 a re-capture merges a strip of a table whose far end
// could pass for the finger (0010); on 278 and 327 a shrinking contour could settle on the
// face's eyes and brows (0018).
TEST(HandTracker, KeepsTheHandWhileItCrossesAFace)
{
    for (std::uint64_t seed :
         {1u, 2u, 3u, 4u, 5u, 6u, 12u, 21u, 23u, 25u, 10u, 17u, 30u, 73u, 22u, 96u, 75u, 44u, 278u, 327u}) {
        const FaceCrossing c = track_face_pass(seed, gc::Eye::Left);
        EXPECT_GT(c.frames, 10) << "seed " << seed << ": the hand must cross the face";
        EXPECT_EQ(c.off, 0) << "seed " << seed << ": lost or off the hand in " << c.off << " of " << c.frames
                            << " crossing frames";
    }
}

// Right-eye face_pass 47: the first templates merge the hand with a box of its colour, and
// the contour slides onto the box while the hand moves on by it. A contour lying on the
// learnt scene must give way at once to a capture of the hand apart from it, before the
// hand reaches the face (docs/adr/0016).
TEST(HandTracker, LeavesTheLearntSceneForACaptureOfTheHand)
{
    const FaceCrossing c = track_face_pass(47, gc::Eye::Right);
    EXPECT_GT(c.frames, 10);
    EXPECT_EQ(c.off, 0) << "lost or off the hand in " << c.off << " of " << c.frames << " crossing frames";
}

// A pointing hand of the proportions capture_quality() ranks as pointing (palm radius 22,
// a finger 10 px wide reaching 2.5 palm radii, pointing up), with sensor noise.
void draw_upright_hand(const DrawnScene& scene, cv::Point palm, cv::Mat3b& out, cv::Mat1b& mask)
{
    mask = cv::Mat1b(scene.background.size(), uchar(0));
    cv::circle(mask, palm, 22, 255, cv::FILLED);
    cv::rectangle(mask, cv::Rect(palm.x - 5, palm.y - 55, 10, 50), 255, cv::FILLED);
    scene.paint(mask, out);
}

// The hand waves with its fingertip against a board of its colour, so the capture is cut
// (not clean); then it moves away and leaves a static likeness of itself where it was,
// which the template fits perfectly. The tracker must notice that nothing moves under its
// contour and go to the hand that does.
TEST(HandTracker, LeavesAStaticLikenessForTheHandThatMoves)
{
    for (std::uint32_t background : {3u, 7u}) {
        cv::setRNGSeed(12);
        DrawnScene scene(background);
        cv::rectangle(scene.background, cv::Rect(80, 55, 60, 42), cv::Scalar(scene.skin), cv::FILLED);
        gc::TrackerParams params = thesis_params();
        params.particles = 300;
        gc::HandTracker tracker(params);
        cv::Mat3b frame;
        cv::Mat1b truth, likeness;
        bool acquired = false;
        int on_hand = 0;
        for (int f = 0; f < 90; ++f) {
            if (f == 12) {
                cv::Mat3b unused;
                draw_upright_hand(scene, {110, 150}, unused, likeness);
                scene.background.setTo(cv::Scalar(scene.skin), likeness);
            }
            const cv::Point palm =
                f < 12 ? cv::Point(110 + (f % 2 ? 3 : -3), 150)
                       : cv::Point(cvRound(240 + 5 * std::sin(0.9 * f)), cvRound(170 + 3 * std::cos(0.7 * f)));
            draw_upright_hand(scene, palm, frame, truth);
            const auto& e = tracker.process(frame);
            if (f == 11) acquired = e.valid() && iou(e.contour, truth) > 0.7;
            if (f >= 60) on_hand += e.valid() && iou(e.contour, truth) >= 0.8;
        }
        EXPECT_TRUE(acquired) << "background " << background;
        EXPECT_EQ(on_hand, 30) << "background " << background << ": on the moving hand in " << on_hand
                               << " of the last 30 frames";
    }
}

TEST(HandTracker, RecoversAfterTheHandLeavesAndReturns)
{
    cv::setRNGSeed(8);
    DrawnScene scene(10);
    gc::TrackerParams params = thesis_params();
    params.particles = 300;
    gc::HandTracker tracker(params);
    cv::Mat3b frame;
    cv::Mat1b truth;
    bool lost = false, back = false;
    for (int f = 0; f < 90; ++f) {
        Pose p = scripted(std::min(f, 20));
        // Frames 25..45 slide out to the right and stay out; then slide back and hold.
        if (f >= 25 && f < 35)
            p.palm.x += 30.0 * (f - 24);
        else if (f >= 35 && f < 55)
            p.palm.x += 1000.0;
        else if (f >= 55 && f < 65)
            p.palm.x += 30.0 * (65 - f);
        scene.render(p.palm, p.deg, p.scale, frame, truth);
        const auto& e = tracker.process(frame);
        if (f >= 40 && f < 55) lost |= e.state == gc::TrackState::Lost;
        if (f >= 75) {
            back = e.valid();
            if (back) {
                EXPECT_GT(iou(e.contour, truth), 0.8) << "frame " << f;
            }
        }
    }
    EXPECT_TRUE(lost) << "the hand out of view must be reported lost";
    EXPECT_TRUE(back) << "the returning hand must be tracked again";
}

TEST(HandTracker, IsDeterministicForASeed)
{
    DrawnScene scene(11);
    gc::TrackerParams params = thesis_params();
    params.particles = 200;
    params.seed = 99;
    gc::HandTracker a(params), b(params);
    cv::Mat3b frame;
    cv::Mat1b truth;
    cv::setRNGSeed(1);
    for (int f = 0; f < 30; ++f) {
        const Pose p = scripted(f);
        scene.render(p.palm, p.deg, p.scale, frame, truth);
        const auto& ea = a.process(frame);
        const auto& eb = b.process(frame);
        ASSERT_EQ(ea.state, eb.state);
        ASSERT_EQ(ea.mean.x, eb.mean.x);
        ASSERT_EQ(ea.contour, eb.contour);
    }
}

// reset() returns a tracker to its initial state: on a fresh tracker it changes nothing, and
// after tracking a while the reset tracker repeats a fresh one's output exactly.
TEST(HandTracker, ResetGivesTheOutputOfAFreshTracker)
{
    DrawnScene scene(12);
    gc::TrackerParams params = thesis_params();
    params.particles = 200;
    params.seed = 7;
    std::vector<cv::Mat3b> frames(30);
    cv::Mat1b truth;
    cv::setRNGSeed(3);
    for (int f = 0; f < 30; ++f) {
        const Pose p = scripted(f);
        scene.render(p.palm, p.deg, p.scale, frames[f], truth);
    }
    gc::HandTracker fresh(params), reset_fresh(params), reset_used(params);
    reset_fresh.reset();
    for (int f = 0; f < 20; ++f) reset_used.process(frames[29 - f]);
    reset_used.reset();
    int tracked = 0;
    for (int f = 0; f < 30; ++f) {
        const gc::EyeEstimate a = fresh.process(frames[f]);
        const gc::EyeEstimate b = reset_fresh.process(frames[f]);
        const gc::EyeEstimate c = reset_used.process(frames[f]);
        for (const gc::EyeEstimate* e : {&b, &c}) {
            ASSERT_EQ(a.state, e->state) << "frame " << f;
            ASSERT_EQ(a.mean.x, e->mean.x) << "frame " << f;
            ASSERT_EQ(a.mean.rotation, e->mean.rotation) << "frame " << f;
            ASSERT_EQ(a.confidence, e->confidence) << "frame " << f;
            ASSERT_EQ(a.contour, e->contour) << "frame " << f;
        }
        tracked += a.state == gc::TrackState::Tracking;
    }
    EXPECT_GT(tracked, 15);  // the comparison covered tracking, not only acquisition
}

// A head that jumps (a fast PTZ turn, a re-homing head) predicts every hypothesis out of
// the frame: the tracker reports the hand lost, without an exception, and finds it again
// once the view is steady.
TEST(HandTracker, SurvivesAHeadJumpThatLeavesNothingToSearch)
{
    const gc::sim::Scene scene(mixed_scene(gc::sim::Preset::Clean, 1));
    gc::HandTracker tracker(seeded_params(1000, 1));
    cv::Mat frame;
    for (int f = 0; f < 40; ++f) {
        scene.render(f, gc::Eye::Left, gc::HeadPose{}, frame, nullptr);
        tracker.process(frame);
    }
    ASSERT_EQ(tracker.estimate().state, gc::TrackState::Tracking);
    for (const double jump : {4000.0, -4000.0}) {
        gc::ImageMotion away;
        away.dx = jump;
        away.dy = jump / 2;
        scene.render(40, gc::Eye::Left, gc::HeadPose{}, frame, nullptr);
        ASSERT_NO_THROW(tracker.process(frame, away));
        EXPECT_EQ(tracker.estimate().state, gc::TrackState::Lost);
        int back = -1;
        for (int f = 41; f < 71 && back < 0; ++f) {
            scene.render(f, gc::Eye::Left, gc::HeadPose{}, frame, nullptr);
            if (tracker.process(frame).state == gc::TrackState::Tracking) back = f;
        }
        EXPECT_GE(back, 0) << "not re-acquired within 30 frames of a jump of " << jump << " px";
    }
}

TEST(HandTracker, BadInputsGiveClearErrors)
{
    gc::HandTracker t;
    EXPECT_THROW(t.process(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(t.process(cv::Mat1b(64, 64, uchar(0))), std::invalid_argument);
    EXPECT_THROW(t.process(cv::Mat(64, 64, CV_8UC4, cv::Scalar::all(0))), std::invalid_argument);
    EXPECT_THROW(t.process(cv::Mat(64, 64, CV_16UC3, cv::Scalar::all(0))), std::invalid_argument);
    EXPECT_THROW(t.process(cv::Mat3b(16, 64)), std::invalid_argument);
    t.process(cv::Mat3b(64, 64, cv::Vec3b(0, 0, 0)));
    try {
        t.process(cv::Mat3b(80, 64, cv::Vec3b(0, 0, 0)));
        FAIL() << "a size change needs reset()";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("size"), std::string::npos);
    }
    t.reset();
    EXPECT_NO_THROW(t.process(cv::Mat3b(80, 64, cv::Vec3b(0, 0, 0))));
    EXPECT_THROW(t.process(cv::Mat3b(80, 64), gc::ImageMotion{NAN, 0, 0, 1}), std::invalid_argument);
    EXPECT_THROW(t.process(cv::Mat3b(80, 64), gc::ImageMotion{0, 0, 0, 0}), std::invalid_argument);
    gc::TrackerParams bad = thesis_params();
    bad.particles = 0;
    EXPECT_THROW(gc::HandTracker{bad}, std::invalid_argument);
    bad = {};
    bad.lost_ratio = 1.5;
    EXPECT_THROW(gc::HandTracker{bad}, std::invalid_argument);
}

TEST(StereoHandTracker, TracksBothEyesLikeTwoMonoTrackers)
{
    DrawnScene left_scene(12), right_scene(13);
    gc::TrackerParams params = thesis_params();
    params.particles = 200;
    gc::StereoHandTracker stereo(params);
    gc::HandTracker mono_left(params);
    cv::Mat3b l, r;
    cv::Mat1b lt, rt;
    for (int f = 0; f < 40; ++f) {
        const Pose p = scripted(f);
        cv::setRNGSeed(100 + f);
        left_scene.render(p.palm, p.deg, p.scale, l, lt);
        right_scene.render(p.palm - cv::Point2d(20, 0), p.deg, p.scale, r, rt);
        const auto s = stereo.process(l, r);
        const auto& m = mono_left.process(l);
        // The left eye runs the same seed as a mono tracker: identical results.
        ASSERT_EQ(s.left.contour, m.contour);
        ASSERT_EQ(s.left.state, m.state);
        if (f >= 20) {
            EXPECT_TRUE(s.left.valid());
            EXPECT_TRUE(s.right.valid());
            if (s.right.valid()) {
                EXPECT_GT(iou(s.right.contour, rt), 0.8);
            }
        }
    }
    // The right eye is seeded differently.
    EXPECT_NE(stereo.eye(gc::Eye::Left).particles()[5].state.x,
              stereo.eye(gc::Eye::Right).particles()[5].state.x + 20.0);
    // Errors from either eye reach the caller; the worker survives them.
    EXPECT_THROW(stereo.process(l, cv::Mat()), std::invalid_argument);
    EXPECT_THROW(stereo.process(cv::Mat(), r), std::invalid_argument);
    stereo.reset();
    EXPECT_NO_THROW(stereo.process(l, r));
}

}  // namespace
