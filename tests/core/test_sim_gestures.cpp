// The renderer's hand gestures: pointing (the hand of every preset), open and fist. The
// silhouettes show what a viewer would count (five spread fingers, one, none), the truth
// says which gesture is shown, and a gesture cycle switches between them over time.
#include "sim/scene.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace {

using gc::Eye;
using gc::Gesture;
using namespace gc::sim;

SceneConfig config(Preset preset, std::uint64_t seed, Gesture gesture, Variety variety = Variety::None)
{
    SceneConfig c;
    c.preset = preset;
    c.seed = seed;
    c.gesture = gesture;
    c.variety = variety;
    c.motion = Motion::Static;
    return c;
}

// The hand face-on, 700 mm in front of the head, pointing up and to the left.
EyeTruth render_face_on(const Scene& scene, Gesture gesture)
{
    HandPose pose;
    pose.palm_mm = {40.0, 40.0, 700.0};
    pose.roll_deg = 110.0;
    pose.gesture = gesture;
    cv::Mat img;
    EyeTruth truth;
    scene.render_pose(pose, 0, Eye::Left, {}, img, &truth);
    return truth;
}

// Gaps between digits: convexity defects of the mask's outline deeper than a fifth of the
// hand's size (the square root of its area). Five spread digits leave four such gaps.
int deep_gaps(const cv::Mat1b& mask)
{
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) return 0;
    const auto& outline = *std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
        return cv::contourArea(a) < cv::contourArea(b);
    });
    std::vector<int> hull;
    cv::convexHull(outline, hull, false, false);
    std::vector<cv::Vec4i> defects;
    cv::convexityDefects(outline, hull, defects);
    const double size = std::sqrt(cv::contourArea(outline));
    int gaps = 0;
    for (const cv::Vec4i& d : defects) gaps += d[3] / 256.0 > 0.2 * size;
    return gaps;
}

// Face-on, the open hand's outline has a gap between every two of its five digits and
// covers more than the pointing hand; the fist has no gap and covers less.
TEST(SimGestures, OpenHandShowsFiveFingersAndFistNone)
{
    for (const Variety variety : {Variety::None, Variety::Wide})
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const Scene scene(config(Preset::Clean, seed, Gesture::Pointing, variety));
            const EyeTruth pointing = render_face_on(scene, Gesture::Pointing);
            const EyeTruth open = render_face_on(scene, Gesture::Open);
            const EyeTruth fist = render_face_on(scene, Gesture::Fist);
            const std::string what = std::string(to_string(variety)) + " seed " + std::to_string(seed);
            EXPECT_GE(deep_gaps(open.mask), 4) << what;
            EXPECT_LE(deep_gaps(pointing.mask), 2) << what;
            EXPECT_EQ(deep_gaps(fist.mask), 0) << what;
            const double area = cv::countNonZero(pointing.mask);
            EXPECT_GE(cv::countNonZero(open.mask) / area, 1.15) << what;
            EXPECT_LE(cv::countNonZero(fist.mask) / area, 0.95) << what;
        }
}

// Only the fingers change: palm, wrist and arm stay where the pointing hand has them, so
// the mask behind the palm centre (away from the fingers and the thumb's root) is the same.
TEST(SimGestures, TheSameHandInEveryGesture)
{
    const Scene scene(config(Preset::Light, 3, Gesture::Pointing, Variety::Wide));
    const EyeTruth pointing = render_face_on(scene, Gesture::Pointing);
    const cv::Point2d axis =
        (pointing.fingertip_px - pointing.palm_px) / cv::norm(pointing.fingertip_px - pointing.palm_px);
    auto behind_palm = [&](const cv::Mat1b& mask) {
        cv::Mat1b out = mask.clone();
        for (int y = 0; y < out.rows; ++y)
            for (int x = 0; x < out.cols; ++x)
                if ((cv::Point2d(x, y) - pointing.palm_px).dot(axis) > -20.0) out(y, x) = 0;
        return out;
    };
    const cv::Mat1b back = behind_palm(pointing.mask);
    ASSERT_GT(cv::countNonZero(back), 300);
    for (const Gesture g : {Gesture::Open, Gesture::Fist}) {
        const EyeTruth other = render_face_on(scene, g);
        EXPECT_LE(cv::norm(other.palm_px - pointing.palm_px), 1e-9) << to_string(g);
        EXPECT_EQ(cv::norm(behind_palm(other.mask), back, cv::NORM_L1), 0.0) << to_string(g);
        EXPECT_GT(cv::norm(other.mask, pointing.mask, cv::NORM_L1), 200.0 * 255.0) << to_string(g);
    }
}

// The truth says which gesture the frame shows; only the pointing hand's fingertip is the
// index fingertip, the open hand reaches farther along its axis and the fist less far.
TEST(SimGestures, TruthReportsTheGesture)
{
    const Scene scene(config(Preset::Clean, 2, Gesture::Pointing));
    HandPose pose = scene.hand_pose(40);
    const HandTruth pointing = scene.hand_truth(pose);
    EXPECT_EQ(pointing.gesture, Gesture::Pointing);
    EXPECT_TRUE(pointing.points());
    pose.gesture = Gesture::Open;
    const HandTruth open = scene.hand_truth(pose);
    pose.gesture = Gesture::Fist;
    const HandTruth fist = scene.hand_truth(pose);
    EXPECT_FALSE(open.points());
    EXPECT_FALSE(fist.points());
    const double reach = cv::norm(pointing.fingertip_mm - pointing.palm_mm);
    EXPECT_GT(cv::norm(open.fingertip_mm - open.palm_mm), reach + 5.0);
    EXPECT_LT(cv::norm(fist.fingertip_mm - fist.palm_mm), reach - 30.0);
    EXPECT_LE(cv::norm(open.direction - pointing.direction), 1e-12);
}

TEST(SimGestures, HeldGestureAndCycle)
{
    SceneConfig c = config(Preset::Clean, 1, Gesture::Open);
    c.motion = Motion::Mixed;
    const Scene held(c);
    cv::Mat img;
    EyeTruth t;
    for (int frame : {0, 100, 700}) {
        EXPECT_EQ(held.hand_pose(frame).gesture, Gesture::Open);
        held.render(frame, Eye::Right, {}, img, &t);
        EXPECT_EQ(t.gesture, Gesture::Open);
    }
    c.gesture = Gesture::Fist;
    c.gesture_cycle_s = 2.0;  // fist 0-2 s, pointing 2-4 s, fist 4-6 s...
    const Scene cycled(c);
    const std::pair<int, Gesture> expected[] = {{0, Gesture::Fist},      {59, Gesture::Fist},
                                                {60, Gesture::Pointing}, {119, Gesture::Pointing},
                                                {120, Gesture::Fist},    {200, Gesture::Pointing}};
    for (const auto& [frame, gesture] : expected) {
        EXPECT_EQ(cycled.hand_pose(frame).gesture, gesture) << "frame " << frame;
        cycled.render(frame, Eye::Left, {}, img, &t);
        EXPECT_EQ(t.gesture, gesture) << "frame " << frame;
    }
}

TEST(SimGestures, RejectsWhatItCannotShow)
{
    SceneConfig c;
    c.gesture = Gesture::Other;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
    c.gesture = Gesture::Open;
    c.gesture_cycle_s = -1.0;
    EXPECT_THROW(Scene{c}, std::invalid_argument);
    c.gesture_cycle_s = 0.0;
    const Scene scene(c);
    HandPose pose;
    pose.gesture = Gesture::Unknown;
    cv::Mat img;
    EXPECT_THROW(scene.render_pose(pose, 0, Eye::Left, {}, img), std::invalid_argument);
}

}  // namespace
