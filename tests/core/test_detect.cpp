#include "detect/motion_detector.hpp"
#include "detect/view_shift.hpp"

#include "background/static_background.hpp"
#include "contour/hand_template.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

// A drawn pointing hand (palm disc, index finger, thumb) of skin colour over a cluttered
// background, with sensor noise.
struct DrawnScene {
    cv::Mat3b background;
    cv::Vec3b skin{105, 140, 205};  // BGR

    explicit DrawnScene(std::uint32_t seed) : background(240, 320)
    {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> c(30, 220), px(0, 319), py(0, 239), sz(8, 60);
        background.setTo(cv::Vec3b(60, 70, 65));
        for (int i = 0; i < 40; ++i)  // non-skin clutter: bluish and greenish blocks
            cv::rectangle(background, cv::Rect(px(rng), py(rng), sz(rng), sz(rng)),
                          cv::Scalar(c(rng), c(rng), c(rng) / 3), cv::FILLED);
    }

    // A static thing of the hand's own colour and brightness, painted into the background.
    void paint_skin(const cv::Rect& box) { cv::rectangle(background, box, cv::Scalar(skin), cv::FILLED); }

    // Sensor noise comes from OpenCV's RNG: seed it with cv::setRNGSeed for a test.
    void render(cv::Point2d palm, double finger_deg, cv::Mat3b& out, cv::Mat1b& mask) const
    {
        mask = cv::Mat1b(background.size(), uchar(0));
        cv::circle(mask, palm, 22, 255, cv::FILLED);
        const double a = finger_deg * std::numbers::pi / 180.0;
        const cv::Point2d dir(std::cos(a), -std::sin(a)), side(-dir.y, dir.x);
        const cv::Point2d base = palm + dir * 15.0, tip = palm + dir * 62.0;
        std::vector<cv::Point> finger{base + side * 5.0, tip + side * 5.0, tip - side * 5.0, base - side * 5.0};
        cv::fillConvexPoly(mask, finger, 255);
        cv::circle(mask, tip, 5, 255, cv::FILLED);
        cv::circle(mask, palm + side * 26.0 + dir * 6.0, 7, 255, cv::FILLED);
        background.copyTo(out);
        out.setTo(skin, mask);
        cv::Mat1s n(out.rows, out.cols * 3);
        cv::randn(n, 0, 2.0);
        cv::Mat3s o;
        out.convertTo(o, CV_16SC3);
        o += n.reshape(3);
        o.convertTo(out, CV_8UC3);
    }
};

double iou(const cv::Mat1b& a, const cv::Mat1b& b)
{
    cv::Mat1b i, u;
    cv::bitwise_and(a, b, i);
    cv::bitwise_or(a, b, u);
    return double(cv::countNonZero(i)) / std::max(1, cv::countNonZero(u));
}

// Pixels of `captured` inside `box` that are not the hand's (`truth`).
int captured_off_hand(const cv::Mat1b& captured, const cv::Mat1b& truth, const cv::Rect& box)
{
    cv::Mat1b off_hand(captured.size(), uchar(0));
    off_hand(box).setTo(255);
    cv::bitwise_and(off_hand, ~truth, off_hand);
    cv::bitwise_and(off_hand, captured, off_hand);
    return cv::countNonZero(off_hand);
}

// Waves the drawn hand by the board-and-strand tests' script (the palm 3 px either side of
// x 150, the finger turning by `turn_deg` steps from 35 deg) until the detector finds it,
// for at most 12 frames. `frame` and `truth` are left with the last frame's; with `learnt`,
// its static scene is given to the detector.
std::optional<gc::Detection> wave_until_found(const DrawnScene& scene, double turn_deg, cv::Mat3b& frame,
                                              cv::Mat1b& truth, gc::StaticBackground* learnt = nullptr)
{
    gc::MotionDetector det;
    std::optional<gc::Detection> found;
    for (int i = 0; i < 12 && !found; ++i) {
        scene.render({150.0 + 3.0 * (i % 2 ? 1 : -1), 130.0}, 35.0 + turn_deg * (i % 3), frame, truth);
        const cv::Rect whole(0, 0, frame.cols, frame.rows);
        found = learnt ? det.process(frame, gc::SkinModel::generic(), true, learnt->find_static(frame, whole))
                       : det.process(frame);
    }
    return found;
}

TEST(MotionDetector, FindsAWavingHand)
{
    cv::setRNGSeed(3);
    DrawnScene scene(5);
    gc::MotionDetector det;
    cv::Mat3b frame;
    cv::Mat1b truth;
    std::optional<gc::Detection> found;
    for (int i = 0; i < 6 && !found; ++i) {
        scene.render({150.0 + 6.0 * (i % 2 ? 1 : -1), 130.0}, 35.0, frame, truth);
        found = det.process(frame);
        if (i == 0) {
            EXPECT_FALSE(found) << "the first frame only primes the detector";
        }
    }
    ASSERT_TRUE(found);
    EXPECT_GT(iou(found->mask, truth), 0.9);
    // The learnt skin colour is the hand's.
    const double sum = 105 + 140 + 205;
    EXPECT_NEAR(found->skin.mean()[0], 205 / sum, 0.01);
    EXPECT_NEAR(found->skin.mean()[1], 140 / sum, 0.01);
}

// The tracker's watch for a moving hand feeds the detector only from history_frames + 1
// frames before it may look, and segments in a second step: the detection must be the one
// a detector that saw every frame gives. A hand waving over the clutter on some frames and holding still on others, so that
// the motion history and the count of frames with motion both matter.
TEST(MotionDetector, PrimedJustBeforeALookFindsWhatAWholeRunFinds)
{
    cv::setRNGSeed(4);
    DrawnScene scene(9);
    const int warm_up = gc::DetectionParams{}.history_frames + 1;
    constexpr int kFrames = 40;
    std::vector<cv::Mat3b> frames(kFrames);
    cv::Mat1b truth;
    for (int i = 0; i < kFrames; ++i) {
        const double step = (i / 5) % 3 == 2 ? 0.0 : 7.0 * (i % 2 ? 1 : -1);  // still for 5 of every 15
        scene.render({120.0 + 2.0 * i + step, 120.0}, 35.0, frames[i], truth);
    }
    int compared_with_a_hand = 0;
    for (int look = warm_up; look < kFrames; ++look) {
        gc::MotionDetector whole, primed;
        std::optional<gc::Detection> from_whole, from_primed;
        for (int i = 0; i <= look; ++i) from_whole = whole.process(frames[i], gc::SkinModel::generic(), i == look);
        // The watch's way: the difference on every frame, the segmentation on the last.
        for (int i = look - warm_up; i <= look; ++i)
            if (primed.difference(frames[i]) && i == look) from_primed = primed.segment_last(frames[i]);
        ASSERT_EQ(from_whole.has_value(), from_primed.has_value()) << look;
        ASSERT_EQ(cv::norm(whole.recent_motion(), primed.recent_motion(), cv::NORM_INF), 0.0) << look;
        if (!from_whole) continue;
        ++compared_with_a_hand;
        EXPECT_EQ(from_whole->box, from_primed->box) << look;
        EXPECT_EQ(cv::countNonZero(from_whole->mask != from_primed->mask), 0) << look;
        EXPECT_EQ(from_whole->motion_support, from_primed->motion_support) << look;
        EXPECT_EQ(from_whole->cut, from_primed->cut) << look;
    }
    EXPECT_GT(compared_with_a_hand, 10);
}

// What changed beyond a box: all of the change without one, none when the box holds it.
TEST(MotionDetector, CountsTheChangeOutsideABox)
{
    DrawnScene scene(9);
    cv::Mat3b a, b;
    cv::Mat1b truth;
    scene.render({120.0, 120.0}, 35.0, a, truth);
    scene.render({132.0, 120.0}, 35.0, b, truth);
    gc::MotionDetector det;
    EXPECT_FALSE(det.difference(a));  // the first frame primes it
    ASSERT_TRUE(det.difference(b));
    const int all = det.changed_outside(cv::Rect());
    EXPECT_GE(all, det.min_changed_pixels());
    EXPECT_EQ(det.changed_outside(cv::Rect(0, 0, a.cols, a.rows)), 0);
    const cv::Rect hand = cv::boundingRect(det.recent_motion());
    EXPECT_EQ(det.changed_outside(hand), 0);
    EXPECT_EQ(det.changed_outside(cv::Rect(hand.x, hand.y, hand.width / 2, hand.height)) +
                  cv::countNonZero(det.recent_motion()(cv::Rect(hand.x, hand.y, hand.width / 2, hand.height))),
              all);
}

TEST(MotionDetector, LeavesOutAStaticSkinObjectTheHandTouches)
{
    cv::setRNGSeed(5);
    DrawnScene scene(7);
    // A skin-coloured board, same tone and brightness, that the fingertip touches.
    scene.paint_skin(cv::Rect(190, 40, 80, 50));
    cv::Mat3b frame;
    cv::Mat1b truth;
    const auto found = wave_until_found(scene, 4.0, frame, truth);
    ASSERT_TRUE(found);
    cv::Mat1b board(frame.size(), uchar(0));
    cv::rectangle(board, cv::Rect(190, 40, 80, 50), 255, cv::FILLED);
    cv::Mat1b on_board;
    cv::bitwise_and(found->mask, board, on_board);
    // At most a rim of the board within reach of the moving finger remains.
    EXPECT_LT(cv::countNonZero(on_board), 0.25 * 80 * 50);
    EXPECT_GT(iou(found->mask, truth), 0.7);
}

TEST(MotionDetector, CutsOffAKnownStaticSceneExactly)
{
    cv::setRNGSeed(5);
    DrawnScene scene(7);
    const cv::Rect board_box(190, 40, 80, 50);
    scene.paint_skin(board_box);
    // The scene, learnt before the hand came in.
    gc::StaticBackground learnt;
    cv::Mat3b frame;
    cv::Mat1b truth;
    for (int i = 0; i < 30; ++i) {
        scene.render({-100.0, -100.0}, 0.0, frame, truth);
        learnt.learn(frame);
    }
    const auto found = wave_until_found(scene, 4.0, frame, truth, &learnt);
    ASSERT_TRUE(found);
    // None of the board, not even the rim near the moving finger that the motion cut keeps.
    EXPECT_LT(captured_off_hand(found->mask, truth, board_box), 0.02 * board_box.area());
    EXPECT_GT(iou(found->mask, truth), 0.85);
    // The hand touched the board: its outline there is the board's cut, so the capture is
    // not ranked clean.
    EXPECT_TRUE(found->cut);
    EXPECT_NE(gc::capture_quality(*found), gc::CaptureQuality::Clean);
    EXPECT_THROW(gc::MotionDetector().process(frame, gc::SkinModel::generic(), true, cv::Mat1b(10, 10, uchar(0))),
                 std::invalid_argument);
}

TEST(MotionDetector, DropsAThinStrandOfSkinColourTheHandTouches)
{
    cv::setRNGSeed(9);
    DrawnScene scene(11);
    // A shelf's edge of the hand's colour, 3 px thick, that the fingertip (about (201, 94))
    // lies on.
    const cv::Rect strand_box(196, 93, 100, 3);
    scene.paint_skin(strand_box);
    cv::Mat3b frame;
    cv::Mat1b truth;
    const auto found = wave_until_found(scene, 0.0, frame, truth);
    ASSERT_TRUE(found);
    // At most the strand's root, where it meets the finger.
    EXPECT_LT(captured_off_hand(found->mask, truth, strand_box), 0.1 * strand_box.area());
    EXPECT_GT(iou(found->mask, truth), 0.9);
    // The finger is kept whole: the fingertip is found within a finger width of the drawn one.
    const cv::Point2d tip = gc::find_hand_landmarks(found->mask).fingertip;
    EXPECT_LT(cv::norm(tip - gc::find_hand_landmarks(truth).fingertip), 10.0);
}

TEST(MotionDetector, LearnsTheHandsBrightnessBesideADarkerObjectOfItsTone)
{
    cv::setRNGSeed(11);
    DrawnScene scene(9);
    // A board of the hand's chromaticity at 45 % of its brightness behind the lower palm:
    // the waving hand uncovers it, so moving skin-chromaticity pixels are of both.
    const cv::Rect board_box(95, 135, 90, 80);
    const cv::Vec3b dark(cv::saturate_cast<uchar>(0.45 * scene.skin[0]), cv::saturate_cast<uchar>(0.45 * scene.skin[1]),
                         cv::saturate_cast<uchar>(0.45 * scene.skin[2]));
    cv::rectangle(scene.background, board_box, cv::Scalar(dark), cv::FILLED);
    gc::MotionDetector det;
    cv::Mat3b frame;
    cv::Mat1b truth;
    std::optional<gc::Detection> found;
    for (int i = 0; i < 12 && !found; ++i) {
        scene.render({150.0 + 4.0 * (i % 2 ? 1 : -1), 140.0 + 2.0 * (i % 3)}, 35.0, frame, truth);
        found = det.process(frame);
    }
    ASSERT_TRUE(found);
    const double hand_brightness = scene.skin[0] + scene.skin[1] + scene.skin[2];
    EXPECT_NEAR(found->skin.brightness_mean(), hand_brightness, 0.1 * hand_brightness);
    cv::Mat1b board(frame.size(), uchar(0)), on_board;
    board(board_box).setTo(255);
    cv::bitwise_and(found->mask, board, on_board);
    cv::bitwise_and(on_board, ~truth, on_board);
    EXPECT_LT(cv::countNonZero(on_board), 0.1 * board_box.area());
    EXPECT_GT(iou(found->mask, truth), 0.8);
}

TEST(MotionDetector, RanksCapturesCleanOverPointingOverUnsure)
{
    // A pointing hand: palm radius 22, a finger 10 px wide reaching 2.5 palm radii.
    cv::Mat1b hand(240, 320, uchar(0));
    cv::circle(hand, {150, 130}, 22, 255, cv::FILLED);
    cv::rectangle(hand, cv::Rect(145, 75, 10, 50), 255, cv::FILLED);
    gc::Detection d{hand, cv::Rect(), gc::SkinModel::generic()};
    EXPECT_EQ(gc::capture_quality(d), gc::CaptureQuality::Clean);
    d.motion_support = 0.8;  // part of the component lay far from the motion
    EXPECT_EQ(gc::capture_quality(d), gc::CaptureQuality::Pointing);
    d.motion_support = 1.0;
    d.cut = true;
    EXPECT_EQ(gc::capture_quality(d), gc::CaptureQuality::Pointing);
    // A touching board merged into the blob: no longer shaped like a pointing hand.
    cv::rectangle(d.mask, cv::Rect(155, 40, 70, 60), 255, cv::FILLED);
    d.cut = false;
    EXPECT_EQ(gc::capture_quality(d), gc::CaptureQuality::Unsure);
    EXPECT_LT(gc::CaptureQuality::Unsure, gc::CaptureQuality::Pointing);
    EXPECT_LT(gc::CaptureQuality::Pointing, gc::CaptureQuality::Clean);
}

TEST(MotionDetector, StaticSceneOrNonSkinMotionGivesNothing)
{
    cv::setRNGSeed(4);
    DrawnScene scene(6);
    gc::MotionDetector det;
    cv::Mat3b frame;
    cv::Mat1b truth;
    for (int i = 0; i < 5; ++i) {
        scene.render({150.0, 130.0}, 35.0, frame, truth);
        EXPECT_FALSE(det.process(frame));
    }
    // A moving blue object is motion but not skin.
    det.reset();
    for (int i = 0; i < 5; ++i) {
        scene.background.copyTo(frame);
        cv::circle(frame, {100 + 10 * i, 100}, 30, cv::Scalar(200, 60, 40), cv::FILLED);
        EXPECT_FALSE(det.process(frame));
    }
}

TEST(MotionDetector, RemembersWhereTheImageChangedForItsHistory)
{
    cv::setRNGSeed(6);
    DrawnScene scene(8);
    gc::DetectionParams params;
    gc::MotionDetector det(params);
    cv::Mat3b frame;
    cv::Mat1b truth;
    EXPECT_TRUE(det.recent_motion().empty());
    scene.render({150.0, 130.0}, 35.0, frame, truth);
    det.process(frame, gc::SkinModel::generic(), false);
    // One step of the hand: its edges changed, the far corner did not.
    scene.render({156.0, 130.0}, 35.0, frame, truth);
    det.process(frame, gc::SkinModel::generic(), false);
    ASSERT_EQ(det.recent_motion().size(), frame.size());
    EXPECT_GT(det.recent_motion()(130, 156 + 22), 0);  // the palm's leading edge
    EXPECT_EQ(cv::countNonZero(det.recent_motion()(cv::Rect(0, 200, 60, 40))), 0);
    // Held still, the change is forgotten after history_frames frames.
    for (int i = 0; i < params.history_frames - 1; ++i) {
        det.process(frame, gc::SkinModel::generic(), false);
        EXPECT_GT(det.recent_motion()(130, 156 + 22), 0) << "frame " << i;
    }
    det.process(frame, gc::SkinModel::generic(), false);
    EXPECT_EQ(det.recent_motion()(130, 156 + 22), 0);
    det.reset();
    EXPECT_TRUE(det.recent_motion().empty());
}

// The difference of two frames of Gaussian noise sigma has sigma * sqrt(2): its threshold
// is 3 of that, also with a fifth of the frame truly moving, and 0 without noise.
TEST(MotionDetector, NoiseThresholdFollowsTheSensorNoise)
{
    cv::setRNGSeed(9);
    for (double sigma : {2.0, 5.0, 8.0}) {
        cv::Mat1s a(480, 640), b(480, 640);
        cv::randn(a, 128, sigma);
        cv::randn(b, 128, sigma);
        cv::Mat1b difference;
        cv::Mat1s d = cv::abs(a - b);
        d.convertTo(difference, CV_8U);
        const double expected = 3.0 * std::sqrt(2.0) * sigma;
        EXPECT_NEAR(gc::frame_noise_threshold(difference), expected, 1.0 + 0.05 * expected) << sigma;
        difference(cv::Rect(0, 0, 640, 96)).setTo(90);  // a fifth of the frame moved
        EXPECT_NEAR(gc::frame_noise_threshold(difference), expected, 1.0 + 0.1 * expected) << sigma;
    }
    EXPECT_EQ(gc::frame_noise_threshold(cv::Mat1b(480, 640, uchar(0))), 0);
    EXPECT_EQ(gc::frame_noise_threshold(cv::Mat1b()), 0);
}

// The view moving as a whole is told from a hand moving in front of a still view, and its
// shift is measured to within the small copy's pixel (here 3 frame pixels).
// The drawn scene with the hand at `hand` (`size` across), seen through a 240x180 view moved
// by `moved` from its place.
cv::Mat3b drawn_view(const DrawnScene& scene, cv::Point2d hand, double size, cv::Point moved = {})
{
    cv::Mat3b frame;
    cv::Mat1b mask;
    scene.render(hand, size, frame, mask);
    return frame(cv::Rect(40, 30, 240, 180) - moved).clone();
}

TEST(ViewShift, TellsAMovedViewFromAHandMovingInFrontOfIt)
{
    const DrawnScene scene(11);
    cv::setRNGSeed(11);
    gc::ViewShift shift;
    for (int i = 0; i < 8; ++i) {
        const gc::ViewChange c =
            shift.update(drawn_view(scene, {150.0 + 12.0 * (i % 2), 130.0 - 6.0 * (i % 3)}, 35.0 + 20.0 * (i % 3)));
        EXPECT_FALSE(c.shifted || c.cut) << "frame " << i;
    }
    const gc::ViewChange moved = shift.update(drawn_view(scene, {150.0, 130.0}, 35.0, {24, -16}));
    ASSERT_TRUE(moved.shifted);
    EXPECT_NEAR(moved.dx, 24.0, 3.0);
    EXPECT_NEAR(moved.dy, -16.0, 3.0);
}

// The second frame is compared with the first, and the first after reset() with nothing.
TEST(ViewShift, ComparesFromTheSecondFrame)
{
    const DrawnScene scene(12);
    cv::setRNGSeed(12);
    const cv::Mat3b still = drawn_view(scene, {150.0, 130.0}, 35.0);
    const cv::Mat3b moved = drawn_view(scene, {150.0, 130.0}, 35.0, {24, -16});
    gc::ViewShift shift;
    EXPECT_FALSE(shift.update(still).shifted);
    const gc::ViewChange second = shift.update(moved);
    ASSERT_TRUE(second.shifted);
    EXPECT_NEAR(second.dx, 24.0, 3.0);
    shift.reset();
    EXPECT_FALSE(shift.update(still).shifted);
    EXPECT_TRUE(shift.update(moved).shifted);
}

TEST(MotionDetector, BadInputsThrow)
{
    gc::MotionDetector det;
    EXPECT_THROW(det.process(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(det.process(cv::Mat1b(40, 40)), std::invalid_argument);
    gc::DetectionParams p;
    p.close_size = 4;
    EXPECT_THROW(gc::MotionDetector{p}, std::invalid_argument);
}

}  // namespace

// A frame that changed almost everywhere (a source whose first frames are black, a cut) makes
// the first noise estimate pass the last grey level; the second pass must stay within the
// histogram (it read past it before, and crashed a side-by-side pipeline now and then).
TEST(MotionDetector, NoiseThresholdOfAFrameThatChangedEverywhere)
{
    const cv::Mat1b changed(480, 640, uchar(200));
    EXPECT_GE(gc::frame_noise_threshold(changed), 255);
    gc::MotionDetector detector;
    const gc::SkinModel prior = gc::SkinModel::generic();
    detector.process(cv::Mat3b(480, 640, cv::Vec3b(0, 0, 0)), prior, true);
    EXPECT_FALSE(detector.process(cv::Mat3b(480, 640, cv::Vec3b(210, 200, 190)), prior, true));
}
