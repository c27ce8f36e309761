// KeyPointFlow: key points follow the image that moves under them, and a point that cannot
// be followed both ways stays where the caller put it.
#include "tracker/key_point_flow.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace {

// A textured frame (random blobs), and the same frame moved by (dx, dy).
cv::Mat textured(int dx, int dy, cv::Size size = {320, 240})
{
    cv::Mat3b frame(size, cv::Vec3b(90, 110, 130));
    cv::RNG rng(7);
    for (int i = 0; i < size.area() / 192; ++i) {
        const cv::Point centre(rng.uniform(0, size.width) + dx, rng.uniform(0, size.height) + dy);
        cv::circle(frame, centre, rng.uniform(2, 7), cv::Scalar(rng.uniform(0, 255), rng.uniform(0, 255), 60),
                   cv::FILLED);
    }
    cv::GaussianBlur(frame, frame, cv::Size(3, 3), 0.0);
    return frame;
}

gc::KeyPointFlow::Points grid()
{
    gc::KeyPointFlow::Points points;
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i] = cv::Point2f(80.0f + 25.0f * (i % 7), 70.0f + 40.0f * (i / 7));
    return points;
}

TEST(KeyPointFlow, PointsFollowTheImage)
{
    gc::KeyPointFlow flow;
    EXPECT_FALSE(flow.ready());
    flow.keep(textured(0, 0), grid());
    ASSERT_TRUE(flow.ready());
    gc::KeyPointFlow::Points points = grid();
    std::array<bool, gc::KeyPointFlow::kPoints> moved;
    flow.carry(textured(6, -4), points, moved);
    const gc::KeyPointFlow::Points start = grid();
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_TRUE(moved[i]) << "point " << i;
        EXPECT_NEAR(points[i].x, start[i].x + 6.0f, 0.3f) << "point " << i;
        EXPECT_NEAR(points[i].y, start[i].y - 4.0f, 0.3f) << "point " << i;
    }
    EXPECT_EQ(flow.kept_points()[3], points[3]);
}

TEST(KeyPointFlow, PointsPlacedFarFromTheLastOnesAreFollowedThere)
{
    // The flow looks only around the points; the landmark model may place them anywhere.
    const cv::Size large(960, 720);
    gc::KeyPointFlow flow;
    flow.keep(textured(0, 0, large), grid());
    gc::KeyPointFlow::Points elsewhere = grid();
    for (cv::Point2f& p : elsewhere) p += cv::Point2f(560.0f, 420.0f);
    flow.replace_points(elsewhere);
    gc::KeyPointFlow::Points points = elsewhere;
    std::array<bool, gc::KeyPointFlow::kPoints> moved;
    flow.carry(textured(-7, 5, large), points, moved);
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_TRUE(moved[i]) << "point " << i;
        EXPECT_NEAR(points[i].x, elsewhere[i].x - 7.0f, 0.3f) << "point " << i;
        EXPECT_NEAR(points[i].y, elsewhere[i].y + 5.0f, 0.3f) << "point " << i;
    }
}

TEST(KeyPointFlow, PointsOnAFeaturelessFrameStayPut)
{
    gc::KeyPointFlow flow;
    flow.keep(textured(0, 0), grid());
    const cv::Mat blank(240, 320, CV_8UC3, cv::Scalar(90, 110, 130));
    gc::KeyPointFlow::Points points = grid();
    std::array<bool, gc::KeyPointFlow::kPoints> moved;
    flow.carry(blank, points, moved);
    std::size_t followed = 0;
    for (std::size_t i = 0; i < points.size(); ++i) followed += moved[i];
    EXPECT_LE(followed, 2u);
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!moved[i]) {
            EXPECT_EQ(points[i], grid()[i]) << "point " << i;
        }
    }
}

}  // namespace
