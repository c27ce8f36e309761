#include "metrics/metrics.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>

namespace {

cv::Mat1b rect_mask(cv::Size size, cv::Rect r)
{
    cv::Mat1b m(size, std::uint8_t{0});
    m(r).setTo(255);
    return m;
}

const cv::Size kSize(64, 48);

TEST(ContourMask, FillsASquareIncludingItsBoundary)
{
    const cv::Mat1b m = gc::contour_mask({{10, 10}, {29, 10}, {29, 29}, {10, 29}}, kSize);
    ASSERT_EQ(m.size(), kSize);
    EXPECT_EQ(cv::countNonZero(m), 20 * 20);
    EXPECT_EQ(m(20, 20), 255);
    EXPECT_EQ(m(5, 5), 0);
    EXPECT_EQ(m(30, 30), 0);
}

TEST(ContourMask, KeepsSubPixelVertices)
{
    // Each scan line's span runs between its edges rounded to the nearest pixel: x in
    // [10.6, 29.4] covers columns 11..29, where truncating the vertices would give 10..29.
    const cv::Mat1b m = gc::contour_mask({{10.6f, 10}, {29.4f, 10}, {29.4f, 29}, {10.6f, 29}}, kSize);
    EXPECT_EQ(cv::countNonZero(m), 19 * 20);
    EXPECT_EQ(m(20, 10), 0);
    EXPECT_EQ(m(20, 11), 255);
    EXPECT_EQ(m(20, 29), 255);
}

TEST(ContourMask, DegenerateAndOutOfFrameContoursGiveEmptyOrClippedMasks)
{
    EXPECT_EQ(cv::countNonZero(gc::contour_mask({}, kSize)), 0);
    EXPECT_EQ(cv::countNonZero(gc::contour_mask({{1, 1}, {5, 5}}, kSize)), 0);
    EXPECT_EQ(cv::countNonZero(gc::contour_mask({{-100, -100}, {-50, -100}, {-50, -50}}, kSize)), 0);
    // A diverged hypothesis with enormous coordinates covers the frame instead of crashing.
    const cv::Mat1b huge =
        gc::contour_mask({{-1e12f, -1e12f}, {1e12f, -1e12f}, {1e12f, 1e12f}, {-1e12f, 1e12f}}, kSize);
    EXPECT_EQ(cv::countNonZero(huge), kSize.area());
}

TEST(ContourMask, RejectsBadInput)
{
    EXPECT_THROW(gc::contour_mask({{1, 1}, {5, 1}, {5, 5}}, cv::Size(0, 10)), std::invalid_argument);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(gc::contour_mask({{1, 1}, {nan, 1}, {5, 5}}, kSize), std::invalid_argument);
}

TEST(MaskIou, KnownOverlaps)
{
    const cv::Mat1b a = rect_mask(kSize, {0, 0, 20, 10});
    EXPECT_DOUBLE_EQ(gc::mask_iou(a, a), 1.0);
    EXPECT_DOUBLE_EQ(gc::mask_iou(a, rect_mask(kSize, {30, 30, 20, 10})), 0.0);
    // Overlap 10 x 10 of two 20 x 10 rectangles: 100 / 300.
    EXPECT_DOUBLE_EQ(gc::mask_iou(a, rect_mask(kSize, {10, 0, 20, 10})), 1.0 / 3.0);
    const cv::Mat1b empty(kSize, std::uint8_t{0});
    EXPECT_DOUBLE_EQ(gc::mask_iou(empty, empty), 1.0);
    EXPECT_DOUBLE_EQ(gc::mask_iou(a, empty), 0.0);
}

TEST(MaskIou, TreatsAnyNonZeroAsInside)
{
    cv::Mat1b a = rect_mask(kSize, {0, 0, 10, 10});
    cv::Mat1b b = a.clone();
    b.setTo(1, a);
    EXPECT_DOUBLE_EQ(gc::mask_iou(a, b), 1.0);
}

TEST(MaskIou, RejectsMismatchedMasks)
{
    EXPECT_THROW(gc::mask_iou(cv::Mat1b(10, 10, std::uint8_t{0}), cv::Mat1b(10, 11, std::uint8_t{0})),
                 std::invalid_argument);
    EXPECT_THROW(gc::mask_iou(cv::Mat1b(), cv::Mat1b()), std::invalid_argument);
}

TEST(Snr, IdenticalMasksHaveInfiniteSnr)
{
    gc::SnrAccumulator acc;
    const cv::Mat1b a = rect_mask(kSize, {5, 5, 20, 10});
    acc.add(a, a);
    EXPECT_EQ(acc.signal(), 400u);
    EXPECT_EQ(acc.noise(), 0u);
    EXPECT_TRUE(std::isinf(acc.snr_db()) && acc.snr_db() > 0);
}

TEST(Snr, DisjointMasksOfEqualAreaAreZeroDecibels)
{
    gc::SnrAccumulator acc;
    const cv::Mat1b a = rect_mask(kSize, {0, 0, 20, 10});
    acc.add(a, rect_mask(kSize, {30, 30, 20, 10}));
    EXPECT_EQ(acc.signal(), 400u);
    EXPECT_EQ(acc.noise(), 400u);
    EXPECT_DOUBLE_EQ(acc.snr_db(), 0.0);
}

TEST(Snr, HalfOverlapAndMissedHandAreThreeDecibels)
{
    const cv::Mat1b ref = rect_mask(kSize, {0, 0, 20, 10});
    gc::SnrAccumulator half;
    half.add(ref, rect_mask(kSize, {10, 0, 20, 10}));  // 100 missed + 100 false
    EXPECT_EQ(half.noise(), 200u);
    EXPECT_NEAR(half.snr_db(), 10.0 * std::log10(2.0), 1e-12);

    gc::SnrAccumulator missed;
    missed.add(ref, cv::Mat1b(kSize, std::uint8_t{0}));
    EXPECT_EQ(missed.noise(), 200u);
    EXPECT_NEAR(missed.snr_db(), 10.0 * std::log10(2.0), 1e-12);
}

TEST(Snr, AccumulatesOverFrames)
{
    const cv::Mat1b ref = rect_mask(kSize, {0, 0, 20, 10});
    gc::SnrAccumulator acc;
    acc.add(ref, ref);                               // signal 400, noise 0
    acc.add(ref, rect_mask(kSize, {0, 0, 10, 10}));  // signal 400, noise 100
    EXPECT_EQ(acc.signal(), 800u);
    EXPECT_EQ(acc.noise(), 100u);
    EXPECT_NEAR(acc.snr_db(), 10.0 * std::log10(8.0), 1e-12);
}

TEST(Snr, NothingAddedIsNaNAndBadInputThrows)
{
    gc::SnrAccumulator acc;
    EXPECT_TRUE(std::isnan(acc.snr_db()));
    EXPECT_THROW(acc.add(cv::Mat1b(4, 4, std::uint8_t{0}), cv::Mat1b(4, 5, std::uint8_t{0})), std::invalid_argument);
    EXPECT_EQ(acc.signal(), 0u);
}

TEST(CentreError, DistanceBetweenCentroids)
{
    const cv::Mat1b a = rect_mask(kSize, {10, 10, 8, 8});
    EXPECT_NEAR(gc::centre_error_px(a, a), 0.0, 1e-12);
    EXPECT_NEAR(gc::centre_error_px(a, rect_mask(kSize, {13, 14, 8, 8})), 5.0, 1e-9);
    EXPECT_TRUE(std::isnan(gc::centre_error_px(a, cv::Mat1b(kSize, std::uint8_t{0}))));
    EXPECT_THROW(gc::centre_error_px(a, cv::Mat1b(3, 3, std::uint8_t{0})), std::invalid_argument);
}

}  // namespace
