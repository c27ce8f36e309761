#include "contour/closed_bspline.hpp"
#include "contour/hand_template.hpp"

#include "drawn_hand.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using gc_test::drawn_hand;

TEST(ClosedBSpline, InterpolatesItsPoints)
{
    std::vector<cv::Point2d> pts;
    for (int i = 0; i < 12; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 12;
        pts.emplace_back(50 + 30 * std::cos(a) + (i % 3) * 2.0, 40 + 20 * std::sin(a));
    }
    const auto s = gc::ClosedBSpline::interpolate(pts);
    ASSERT_EQ(s.size(), 12);
    for (int i = 0; i < 12; ++i) {
        const cv::Point2d p = s.point(i);
        EXPECT_NEAR(p.x, pts[i].x, 1e-9);
        EXPECT_NEAR(p.y, pts[i].y, 1e-9);
    }
    // Closed: the parameter wraps.
    EXPECT_NEAR(s.point(12.0).x, pts[0].x, 1e-9);
    EXPECT_NEAR(s.point(-0.5).x, s.point(11.5).x, 1e-9);
}

TEST(ClosedBSpline, NormalsPointOutwardForBothOrientations)
{
    for (int dir : {1, -1}) {
        std::vector<cv::Point2d> pts;
        for (int i = 0; i < 16; ++i) {
            const double a = dir * 2.0 * std::numbers::pi * i / 16;
            pts.emplace_back(100 + 40 * std::cos(a), 80 + 25 * std::sin(a));
        }
        const auto s = gc::ClosedBSpline::interpolate(pts);
        for (int k = 0; k < 64; ++k) {
            const double u = k * 16.0 / 64;
            const cv::Point2d p = s.point(u);
            const cv::Point2d n = s.outward_normal(u);
            EXPECT_NEAR(std::hypot(n.x, n.y), 1.0, 1e-9);
            // Outward on an ellipse centred at (100, 80): away from the centre.
            EXPECT_GT((p.x - 100) * n.x + (p.y - 80) * n.y, 0.0) << "u=" << u << " dir=" << dir;
            // Perpendicular to the tangent.
            const cv::Point2d d = s.derivative(u);
            EXPECT_NEAR(d.x * n.x + d.y * n.y, 0.0, 1e-9);
        }
    }
}

TEST(ClosedBSpline, RejectsDegenerateInput)
{
    std::vector<cv::Point2d> three{{0, 0}, {1, 0}, {0, 1}};
    EXPECT_THROW(gc::ClosedBSpline::interpolate(three), std::invalid_argument);
    std::vector<cv::Point2d> dup{{0, 0}, {0, 0}, {1, 1}, {0, 1}};
    EXPECT_THROW(gc::ClosedBSpline::interpolate(dup), std::invalid_argument);
    std::vector<cv::Point2d> line{{0, 0}, {1, 0}, {2, 0}, {3, 0}};
    EXPECT_THROW(gc::ClosedBSpline::interpolate(line), std::invalid_argument);
    std::vector<cv::Point2d> nan{{0, 0}, {1, 0}, {NAN, 1}, {0, 1}};
    EXPECT_THROW(gc::ClosedBSpline::interpolate(nan), std::invalid_argument);
}

TEST(HandTemplate, FindsPalmAndFingertipFromTheShape)
{
    for (double angle : {0.0, 70.0, 160.0, 250.0}) {
        const cv::Point2d palm(160, 120);
        const auto mask = drawn_hand({320, 240}, palm, angle, 1.0);
        const auto lm = gc::find_hand_landmarks(mask);
        EXPECT_LT(std::hypot(lm.palm.x - palm.x, lm.palm.y - palm.y), 4.0) << angle;
        const double a = angle * std::numbers::pi / 180.0;
        const cv::Point2d tip = palm + cv::Point2d(std::cos(a), -std::sin(a)) * 67.0;
        EXPECT_LT(std::hypot(lm.fingertip.x - tip.x, lm.fingertip.y - tip.y), 3.0) << angle;
        EXPECT_NEAR(lm.palm_radius, 22.0, 2.0);
    }
}

// A hand merged with a static skin-coloured strip that reaches farther than its finger:
// the shape alone puts the fingertip at the strip's end; the motion of the waving hand,
// where the hand's own outline changed, puts it back on the finger, even with a few
// changed pixels at the strip's end (where a moving sleeve passes it), and ranks the
// shape as not pointing.
TEST(HandTemplate, FindsTheFingertipWhereTheShapeMoved)
{
    const cv::Size size(320, 240);
    const cv::Point2d palm(150, 100);
    const cv::Mat1b hand = drawn_hand(size, palm, 0.0, 1.0);  // finger to +x, tip at x = 217
    cv::Mat1b merged = hand.clone();
    cv::line(merged, {150, 110}, {90, 200}, 255, 12);  // the strip: ~100 px from the palm
    const auto still = gc::find_hand_landmarks(merged);
    EXPECT_GT(still.fingertip.y, 180.0) << "the strip's end is the farthest point";

    // The hand moved by (3, 2) px since a few frames: its outline's strips changed.
    cv::Mat1b before = cv::Mat1b::zeros(size), motion;
    hand(cv::Rect(3, 2, size.width - 3, size.height - 2))
        .copyTo(before(cv::Rect(0, 0, size.width - 3, size.height - 2)));
    cv::bitwise_xor(hand, before, motion);
    motion(cv::Rect(86, 194, 8, 8)).setTo(255);  // a sleeve passing the strip's end
    const auto moving = gc::find_hand_landmarks(merged, motion);
    EXPECT_LT(std::hypot(moving.fingertip.x - 217, moving.fingertip.y - 100), 4.0) << moving.fingertip;
    // What the hand is merged with reaches farther than the finger: not a pointing hand's
    // shape, though the hand alone is.
    const gc::HandProportions with_strip = gc::hand_proportions(merged, motion);
    ASSERT_TRUE(with_strip.valid);
    EXPECT_FALSE(with_strip.farthest_moved);
    EXPECT_FALSE(with_strip.pointing());
    EXPECT_TRUE(gc::hand_proportions(hand, motion).farthest_moved);

    // Nothing of the shape moved: the shape alone decides.
    const auto unmoved = gc::find_hand_landmarks(merged, cv::Mat1b::zeros(size));
    EXPECT_EQ(unmoved.fingertip, still.fingertip);
    EXPECT_THROW(gc::find_hand_landmarks(merged, cv::Mat1b::zeros(10, 10)), std::invalid_argument);
}

// on_finger marks the outline along the index finger: the fingertip and the finger's sides,
// not the palm's far side or the thumb.
TEST(HandTemplate, KnowsWhichOutlinePointsAreOnTheFinger)
{
    const auto mask = drawn_hand({320, 240}, {160, 120}, 0.0, 1.0);  // finger to +x
    const auto t = gc::HandTemplate::from_mask(mask);
    EXPECT_TRUE(t.on_finger(t.fingertip));
    int finger = 0;
    for (const auto& u : t.outline) {
        if (!t.on_finger(u)) continue;
        ++finger;
        EXPECT_GT(u.x, 20.0) << "beyond the palm disc, towards the tip";
        EXPECT_LT(std::abs(u.y), 12.0) << "within the finger's width";
    }
    EXPECT_GT(finger, 20);
    EXPECT_FALSE(t.on_finger({-22.0f, 0.0f}));  // the palm's far side
}

TEST(HandTemplate, OutlineIsFaithfulAndDenserOnTheFinger)
{
    const cv::Point2d palm(160, 120);
    const auto mask = drawn_hand({320, 240}, palm, 30.0, 1.2);
    const auto t = gc::HandTemplate::from_mask(mask);
    ASSERT_EQ(t.outline.size(), 128u);
    ASSERT_EQ(t.points.size(), 48u);
    // Filled, the outline reproduces the mask.
    std::vector<cv::Point> poly;
    for (const auto& p : t.outline) poly.emplace_back(cvRound(p.x + t.origin_px.x), cvRound(p.y + t.origin_px.y));
    cv::Mat1b filled(mask.size(), uchar(0));
    cv::fillPoly(filled, std::vector<std::vector<cv::Point>>{poly}, 255);
    cv::Mat1b inter, uni;
    cv::bitwise_and(filled, mask, inter);
    cv::bitwise_or(filled, mask, uni);
    EXPECT_GT(double(cv::countNonZero(inter)) / cv::countNonZero(uni), 0.93);
    // Normals point away from the hand: a step outward leaves the mask, inward stays in.
    int outside = 0, inside = 0;
    for (std::size_t i = 0; i < t.points.size(); ++i) {
        const cv::Point2d p = cv::Point2d(t.points[i]) + t.origin_px;
        const cv::Point2d n(t.normals[i]);
        const cv::Point out = p + 3.0 * n, in = p - 3.0 * n;
        outside += mask(out) == 0;
        inside += mask(in) != 0;
    }
    EXPECT_GE(outside, 45);
    EXPECT_GE(inside, 42);  // the finger is 10-12 px wide: a few inner probes cross it
    // Finger normals carry more weight, and there are more of them per unit length.
    const cv::Point2f tip = t.fingertip;
    float finger_w = 1.0f, palm_w = 1.0f;  // the lightest weight of each part
    int finger_n = 0;
    for (std::size_t i = 0; i < t.points.size(); ++i) {
        const bool finger = std::hypot(t.points[i].x - tip.x, t.points[i].y - tip.y) < 20.0;
        float& w = finger ? finger_w : palm_w;
        w = std::min(w, t.weights[i]);
        finger_n += finger;
    }
    EXPECT_GT(finger_w, palm_w);
    EXPECT_GE(finger_n, 7);  // ~40 px of outline within 20 px of the tip: 48 normals would give ~4 if even
}

// Curled fingers make knuckle bumps a few pixels apart along the palm: the template's
// spline must follow them, not cut across them as sparser points would (docs/adr/0006).
TEST(HandTemplate, OutlineFollowsTheKnuckles)
{
    const cv::Point2d palm(160, 120);
    cv::Mat1b mask = drawn_hand({320, 240}, palm, 30.0, 1.2);
    const double a = 30.0 * std::numbers::pi / 180.0;
    for (int k = 0; k < 4; ++k) {  // four knuckles below the finger, on the palm's rim
        const double b = a - std::numbers::pi / 2 - 0.35 * k;
        cv::circle(mask, palm + 26.0 * cv::Point2d(std::cos(b), -std::sin(b)), 5, 255, cv::FILLED);
    }
    const auto t = gc::HandTemplate::from_mask(mask);
    std::vector<cv::Point2f> outline;
    for (const auto& p : t.outline) outline.emplace_back(p + cv::Point2f(t.origin_px));
    std::vector<std::vector<cv::Point>> raster;
    cv::findContours(mask.clone(), raster, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    ASSERT_EQ(raster.size(), 1u);
    double worst = 0.0, sum = 0.0;
    for (const cv::Point& q : raster[0]) {
        const double d = std::abs(cv::pointPolygonTest(outline, cv::Point2f(q), true));
        worst = std::max(worst, d);
        sum += d;
    }
    // The raster chain runs through the boundary pixels' centres, half a pixel inside the
    // outline of the shape they cover.
    EXPECT_LT(sum / raster[0].size(), 0.5);
    EXPECT_LT(worst, 1.6);
}

// The proportions tell a pointing hand from one merged with a touching object: a box at the
// fingertip makes the finger thick, a box beside the palm moves the palm into it.
TEST(HandProportions, FlagAHandMergedWithATouchingObject)
{
    const cv::Size size(320, 240);
    const cv::Mat1b hand = drawn_hand(size, {150, 140}, 60.0, 1.0);
    const gc::HandProportions plain = gc::hand_proportions(hand);
    ASSERT_TRUE(plain.valid);
    EXPECT_LT(plain.finger_width, 0.33);
    EXPECT_GT(plain.reach, 1.8);
    EXPECT_LT(plain.reach, 3.3);

    // A 30 x 30 box over the fingertip (60 deg: up and to the right).
    cv::Mat1b at_tip = hand.clone();
    const double a = 60.0 * std::numbers::pi / 180.0;
    const cv::Point2d tip(150 + 62 * std::cos(a), 140 - 62 * std::sin(a));
    cv::rectangle(at_tip, cv::Rect(cvRound(tip.x) - 10, cvRound(tip.y) - 25, 30, 30), 255, cv::FILLED);
    const gc::HandProportions merged = gc::hand_proportions(at_tip);
    ASSERT_TRUE(merged.valid);
    EXPECT_FALSE(merged.pointing());
    EXPECT_GT(merged.finger_width, plain.finger_width + 0.2);

    // A large box touching the palm's side: its middle becomes the "palm".
    cv::Mat1b beside = hand.clone();
    cv::rectangle(beside, cv::Rect(60, 110, 70, 60), 255, cv::FILLED);
    EXPECT_FALSE(gc::hand_proportions(beside).pointing());

    EXPECT_FALSE(gc::hand_proportions(cv::Mat1b(size, uchar(0))).valid);
}

TEST(HandTemplate, BadMasksGiveClearErrors)
{
    EXPECT_THROW(gc::HandTemplate::from_mask(cv::Mat1b()), std::invalid_argument);
    EXPECT_THROW(gc::HandTemplate::from_mask(cv::Mat3b(50, 50)), std::invalid_argument);
    EXPECT_THROW(gc::HandTemplate::from_mask(cv::Mat1b(50, 50, uchar(0))), std::invalid_argument);
    cv::Mat1b disc(200, 200, uchar(0));
    cv::circle(disc, {100, 100}, 40, 255, cv::FILLED);
    try {
        gc::HandTemplate::from_mask(disc);
        FAIL() << "a disc has no finger";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("finger"), std::string::npos);
    }
}

}  // namespace
