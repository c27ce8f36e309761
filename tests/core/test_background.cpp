#include "background/static_background.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <stdexcept>

namespace {

const cv::Rect kWhole(0, 0, 160, 120);

// A textured static scene with sensor noise (sd 2 levels).
cv::Mat3b noisy(const cv::Mat3b& scene, int seed)
{
    cv::RNG rng(seed);
    cv::Mat3s noise(scene.size());
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
    cv::Mat3s sum;
    scene.convertTo(sum, CV_16SC3);
    sum += noise;
    cv::Mat3b out;
    sum.convertTo(out, CV_8UC3);
    return out;
}

cv::Mat3b textured_scene()
{
    cv::Mat3b scene(kWhole.size(), cv::Vec3b(90, 120, 150));
    cv::rectangle(scene, cv::Rect(20, 20, 50, 40), cv::Scalar(120, 150, 200), cv::FILLED);  // skin-like board
    cv::circle(scene, {120, 70}, 25, cv::Scalar(40, 60, 70), cv::FILLED);
    return scene;
}

int count_in(const cv::Mat1b& map, const cv::Rect& r) { return cv::countNonZero(map(r)); }

}  // namespace

TEST(StaticBackground, KnowsNothingUntilItHasLearntAndTrustedTheScene)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    EXPECT_TRUE(bg.find_static(scene, kWhole).empty());
    bg.learn(noisy(scene, 1));
    // One frame is a median, but not a trusted one.
    EXPECT_EQ(cv::countNonZero(bg.find_static(noisy(scene, 2), kWhole)), 0);
    // Each call learns every other row: 40 calls are 20 frames per pixel.
    for (int i = 3; i < 42; ++i) bg.learn(noisy(scene, i));
    const cv::Mat1b& found = bg.find_static(noisy(scene, 99), kWhole);
    ASSERT_EQ(found.size(), scene.size());
    // All of it but the outermost pixels, whose 8 neighbours are not all inside.
    EXPECT_GT(cv::countNonZero(found), 0.95 * kWhole.area());
}

TEST(StaticBackground, AnObjectInFrontOfTheSceneIsNotTheScene)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    for (int i = 0; i < 40; ++i) bg.learn(noisy(scene, i));
    cv::Mat3b with_hand = noisy(scene, 100);
    const cv::Rect hand(60, 40, 30, 40);
    cv::rectangle(with_hand, hand, cv::Scalar(110, 140, 190), cv::FILLED);
    const cv::Mat1b& found = bg.find_static(with_hand, kWhole);
    EXPECT_EQ(count_in(found, hand), 0);
    // The map only covers the region asked for.
    const cv::Rect roi(0, 0, 50, 50);
    const cv::Mat1b& part = bg.find_static(with_hand, roi);
    EXPECT_GT(count_in(part, cv::Rect(1, 1, 48, 48)), 0.95 * 48 * 48);
    EXPECT_EQ(cv::countNonZero(part) - count_in(part, roi), 0);
}

TEST(StaticBackground, AHandHeldStillInTheKeepOutIsNeverLearnt)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    for (int i = 0; i < 20; ++i) bg.learn(noisy(scene, i));
    // The hand arrives and stays still for longer than the median needs to follow it (40
    // levels at one level per two frames); the region around it is kept out, as the
    // tracker does.
    const cv::Rect hand(60, 40, 30, 40);
    const cv::Rect keep_out(52, 32, 46, 56);
    cv::Mat3b with_hand;
    for (int i = 0; i < 160; ++i) {
        with_hand = noisy(scene, 200 + i);
        cv::rectangle(with_hand, hand, cv::Scalar(110, 140, 190), cv::FILLED);
        bg.learn(with_hand, keep_out);
    }
    EXPECT_EQ(count_in(bg.find_static(with_hand, kWhole), hand), 0);
    // Without the keep-out the same still hand becomes part of the scene.
    gc::StaticBackground learns_all;
    for (int i = 0; i < 20; ++i) learns_all.learn(noisy(scene, i));
    for (int i = 0; i < 160; ++i) {
        with_hand = noisy(scene, 200 + i);
        cv::rectangle(with_hand, hand, cv::Scalar(110, 140, 190), cv::FILLED);
        learns_all.learn(with_hand);
    }
    EXPECT_GT(count_in(learns_all.find_static(with_hand, kWhole), hand), 0.8 * hand.area());
}

TEST(StaticBackground, TheSceneUnderTheKeepOutIsStillRecognisedWhenUncovered)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    const cv::Rect keep_out(10, 10, 70, 60);  // over the board, from the start
    for (int i = 0; i < 40; ++i) bg.learn(noisy(scene, i), keep_out);
    // Trust is counted against the held median, so the board is known although its
    // median never moved (it is one noisy frame, so a few more pixels miss than where the
    // median settled).
    EXPECT_GT(count_in(bg.find_static(noisy(scene, 77), kWhole), cv::Rect(21, 21, 48, 38)), 0.85 * 48 * 38);
}

TEST(StaticBackground, ACoveredPatchLosesItsTrustAndSweptPatchesAreStillLearnt)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    const cv::Rect patch(100, 20, 20, 20);
    // A hand sweeping over the patch every third frame: trust counts 2 up, 1 down.
    for (int i = 0; i < 120; ++i) {
        cv::Mat3b frame = noisy(scene, i);
        if (i % 3 == 1) cv::rectangle(frame, patch, cv::Scalar(110, 140, 190), cv::FILLED);
        bg.learn(frame);
    }
    EXPECT_GT(count_in(bg.find_static(noisy(scene, 500), kWhole), patch), 0.9 * patch.area());
}

TEST(StaticBackground, ResetAndANewFrameSizeStartAgain)
{
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    for (int i = 0; i < 30; ++i) bg.learn(noisy(scene, i));
    bg.reset();
    EXPECT_TRUE(bg.empty());
    EXPECT_TRUE(bg.find_static(scene, kWhole).empty());
    for (int i = 0; i < 30; ++i) bg.learn(noisy(scene, i));
    cv::Mat3b larger;
    cv::resize(scene, larger, {}, 2, 2);
    EXPECT_TRUE(bg.find_static(larger, kWhole).empty());
    bg.learn(larger);
    EXPECT_EQ(cv::countNonZero(bg.find_static(larger, cv::Rect(0, 0, larger.cols, larger.rows))), 0);
}

TEST(StaticBackground, BadInputsThrow)
{
    EXPECT_THROW(gc::StaticBackground(gc::StaticBackgroundParams{0, 15}), std::invalid_argument);
    EXPECT_THROW(gc::StaticBackground(gc::StaticBackgroundParams{8, 256}), std::invalid_argument);
    gc::StaticBackground bg;
    EXPECT_THROW(bg.learn(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(bg.learn(cv::Mat1b(10, 10, uchar(0))), std::invalid_argument);
    const cv::Mat3b scene = textured_scene();
    bg.learn(scene);
    EXPECT_THROW(bg.learn(scene, cv::Rect(0, 0, 10, 10), cv::Mat1b(5, 5, uchar(0))), std::invalid_argument);
    // A grey frame has no static scene to show.
    EXPECT_TRUE(bg.find_static(cv::Mat1b(scene.size(), uchar(0)), kWhole).empty());
}

TEST(StaticBackground, LooksAtOnePixelAsTheMapDoesAndTellsWhatMovedFromWhatIsUnknown)
{
    using Look = gc::StaticBackground::Look;
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    EXPECT_EQ(bg.look(scene, {80, 60}), Look::Unknown);  // nothing learnt yet
    bg.learn(noisy(scene, 1));
    EXPECT_EQ(bg.look(noisy(scene, 2), {80, 60}), Look::Unknown);  // a median, not trusted
    for (int i = 3; i < 42; ++i) bg.learn(noisy(scene, i));
    cv::Mat3b with_hand = noisy(scene, 100);
    const cv::Rect hand(60, 40, 30, 40);
    cv::rectangle(with_hand, hand, cv::Scalar(110, 140, 190), cv::FILLED);
    const cv::Mat1b found = bg.find_static(with_hand, kWhole).clone();
    // Wherever the map says scene, look() does; inside the object it says foreground, and
    // just beside it (a neighbour differs) neither.
    int disagree = 0;
    for (int y = 0; y < kWhole.height; ++y)
        for (int x = 0; x < kWhole.width; ++x)
            disagree += (found(y, x) != 0) != (bg.look(with_hand, {x, y}) == Look::Scene);
    EXPECT_EQ(disagree, 0);
    EXPECT_EQ(bg.look(with_hand, {75, 60}), Look::Foreground);
    EXPECT_EQ(bg.look(with_hand, {hand.x - 1, 60}), Look::Unsure);
    EXPECT_EQ(bg.look(with_hand, {30, 100}), Look::Scene);
    // A pixel of a frame of another size, or of another type, is unknown.
    EXPECT_EQ(bg.look(cv::Mat3b(60, 80, cv::Vec3b(0, 0, 0)), {10, 10}), Look::Unknown);
    cv::Mat1b grey;
    cv::cvtColor(with_hand, grey, cv::COLOR_BGR2GRAY);
    EXPECT_EQ(bg.look(grey, {75, 60}), Look::Unknown);
}

TEST(StaticBackground, ASceneTheFrameNoLongerMatchesIsForgottenNotCalledForeground)
{
    using Look = gc::StaticBackground::Look;
    gc::StaticBackground bg;
    const cv::Mat3b scene = textured_scene();
    for (int i = 0; i < 40; ++i) bg.learn(noisy(scene, i));  // trust 20 per pixel
    // The scene changes for good (a light switched on): trust drains, one miss per two
    // frames, and the median no longer stands for the scene.
    cv::Mat3b lit;
    cv::add(scene, cv::Scalar(40, 40, 40), lit);
    int frames = 0;
    while (bg.look(noisy(lit, 500 + frames), {80, 60}) == Look::Foreground && frames < 100)
        bg.learn(noisy(lit, 500 + frames++));
    // Trust 20 falls below 8 after 13 misses, 26 frames.
    EXPECT_GE(frames, 24);
    EXPECT_LE(frames, 28);
    EXPECT_EQ(bg.look(noisy(lit, 999), {80, 60}), Look::Unknown);
    // The median then follows the lit scene (40 levels, one per two frames) and is trusted
    // again 8 matches later.
    for (int i = 0; i < 120; ++i) bg.learn(noisy(lit, 1000 + i));
    EXPECT_EQ(bg.look(noisy(lit, 2000), {80, 60}), Look::Scene);
}
