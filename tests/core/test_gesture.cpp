// The gesture classifier on MediaPipe's reference landmarks of the real pair: the pointing
// frames read as pointing, the others (open hand, fist, a lone little finger) do not, and
// the answer does not depend on the hand's size or turn in the image.
#include "detect/gesture.hpp"

#include "real_pair.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <iostream>
#include <string>

namespace {

gc::HandKeyPoints as_landmarks(const std::array<cv::Point2f, 21>& points)
{
    gc::HandKeyPoints hand;
    hand.points = points;
    hand.presence = 1.0f;
    return hand;
}

TEST(Gesture, PointingOnThePointingFramesOfBothViews)
{
    for (int view = 0; view < 2; ++view) {
        const std::vector<gc_test::ReferenceHand> reference = gc_test::load_reference(view);
        ASSERT_EQ(int(reference.size()), gc_test::kRealPairFrames);
        int pointing_frames = 0, pointing_hits = 0, other_frames = 0, other_hits = 0;
        for (int i = 0; i < int(reference.size()); ++i) {
            if (!reference[i]) continue;
            const bool pointing = gc::classify_gesture(as_landmarks(*reference[i])) == gc::Gesture::Pointing;
            if (gc_test::is_pointing_frame(i)) {
                ++pointing_frames;
                pointing_hits += pointing;
            } else {
                ++other_frames;
                other_hits += pointing;
            }
        }
        std::cout << "view " << view << ": pointing on " << pointing_hits << " of " << pointing_frames
                  << " pointing frames, on " << other_hits << " of " << other_frames << " others\n";
        ASSERT_GT(other_frames, 100);
        EXPECT_GE(pointing_hits, 0.9 * pointing_frames) << "view " << view;
        EXPECT_LE(other_hits, 0.1 * other_frames) << "view " << view;
    }
}

// Every annotated frame of one view, each hand turned (in steps of 30 degrees) and scaled
// (from 0.3 to 3) about an arbitrary point, keeps its gesture and its extended fingers.
TEST(Gesture, SameAnswerAtAnyScaleAndTurn)
{
    const std::vector<gc_test::ReferenceHand> reference = gc_test::load_reference(1);
    int compared = 0;
    for (int i = 0; i < int(reference.size()); i += 3) {
        if (!reference[i]) continue;
        const gc::HandKeyPoints hand = as_landmarks(*reference[i]);
        for (int step = 1; step < 12; ++step) {
            const double angle = step * 30.0, scale = 0.3 * std::pow(10.0, step / 11.0);
            const cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(100.0f, -40.0f), angle, scale);
            gc::HandKeyPoints moved = hand;
            cv::transform(hand.points, moved.points, m);
            ASSERT_EQ(gc::extended_fingers(moved), gc::extended_fingers(hand))
                << "frame " << i << ", turned " << angle << " deg, scaled " << scale;
            ++compared;
        }
    }
    EXPECT_GT(compared, 1000);
}

TEST(Gesture, Names)
{
    EXPECT_EQ(gc::to_string(gc::Gesture::Pointing), "pointing");
    EXPECT_EQ(gc::to_string(gc::Gesture::Open), "open");
    EXPECT_EQ(gc::to_string(gc::Gesture::Fist), "fist");
    EXPECT_EQ(gc::to_string(gc::Gesture::Other), "other");
}

}  // namespace
