#include "contour/hand_template.hpp"
#include "measure/contour_fit.hpp"
#include "measure/contour_measurement.hpp"
#include "measure/edge_search.hpp"

#include "drawn_hand.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

// A horizontal membership profile: skin (255) for x < edge, background (0) beyond, with a
// linear ramp over one pixel like an anti-aliased boundary.
cv::Mat1b step_map(double edge)
{
    cv::Mat1b m(20, 60);
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x)
            m(y, x) = cv::saturate_cast<uchar>(255.0 * std::clamp(edge - x + 0.5, 0.0, 1.0));
    return m;
}

TEST(EdgeSearch, FindsAStepAtTheRightSubPixelOffset)
{
    for (double edge : {30.0, 30.25, 30.5, 30.8}) {
        const auto m = step_map(edge);
        float off = 0;
        // From x = 28, pointing along +x: the 128 level is crossed near x = edge.
        ASSERT_TRUE(gc::find_skin_edge_fast(m, 28.0f, 10.0f, 1.0f, 0.0f, 8, off));
        EXPECT_NEAR(28.0 + off, edge, 0.1) << edge;
        double offd = 0;
        ASSERT_TRUE(gc::find_skin_edge_precise(m, {28.0, 10.0}, {1.0, 0.0}, 8.0, 0.25, offd));
        EXPECT_NEAR(28.0 + offd, edge, 0.1) << edge;
    }
}

TEST(EdgeSearch, IgnoresSkinClutterBeyondTheEdge)
{
    auto m = step_map(30.0);
    // A skin-coloured object just outside the hand, nearer the hypothesis than the true
    // edge is: the outward search stops at the hand's own edge.
    cv::rectangle(m, cv::Rect(33, 0, 6, 20), 255, cv::FILLED);
    float off = 0;
    ASSERT_TRUE(gc::find_skin_edge_fast(m, 34.0f, 10.0f, 1.0f, 0.0f, 8, off));
    EXPECT_NEAR(34.0 + off, 30.0, 0.2);
    // The clutter's own far edge (x = 39) is nearer to a hypothesis at x = 37 than the hand
    // edge is, yet the hand's edge is still the one found when it is in the window.
    ASSERT_TRUE(gc::find_skin_edge_fast(m, 37.0f, 10.0f, 1.0f, 0.0f, 8, off));
    EXPECT_NEAR(37.0 + off, 30.0, 0.2);
}

TEST(EdgeSearch, NoEdgeInsideOrOutsideOrOffTheImage)
{
    const auto m = step_map(30.0);
    float off = 0;
    EXPECT_FALSE(gc::find_skin_edge_fast(m, 10.0f, 10.0f, 1.0f, 0.0f, 5, off));  // all skin
    EXPECT_FALSE(gc::find_skin_edge_fast(m, 50.0f, 10.0f, 1.0f, 0.0f, 5, off));  // no skin
    // Skin running off the image: the border is background, so there is an edge there.
    EXPECT_TRUE(gc::find_skin_edge_fast(m, 2.0f, 10.0f, -1.0f, 0.0f, 5, off));
    EXPECT_NEAR(2.0 - off, -0.5, 0.6);
    EXPECT_FALSE(gc::find_skin_edge_fast(m, -100.0f, -100.0f, 1.0f, 0.0f, 5, off));
}

TEST(EdgeSearch, TellsSkinRunningIntoSkinFromNoSkin)
{
    const auto m = step_map(30.0);
    float off = 0;
    bool beyond = false;
    EXPECT_FALSE(gc::find_skin_edge_fast(m, 10.0f, 10.0f, 1.0f, 0.0f, 5, off, &beyond));
    EXPECT_TRUE(beyond);  // skin into skin
    EXPECT_FALSE(gc::find_skin_edge_fast(m, 50.0f, 10.0f, 1.0f, 0.0f, 5, off, &beyond));
    EXPECT_FALSE(beyond);  // no skin at all
}

// Grey levels `inside` for x < edge and `outside` beyond, blurred like a lens.
cv::Mat1b grey_step(int edge, int inside, int outside)
{
    cv::Mat1b g(20, 60, uchar(outside));
    g.colRange(0, edge).setTo(inside);
    cv::GaussianBlur(g, g, cv::Size(5, 5), 0.8);
    return g;
}

TEST(EdgeSearch, FindsTheStrongestGreyStepAndIgnoresWeakOnes)
{
    float off = 0;
    // A darker hand rim (140) against a face (170): the step lies between x = 29 and 30.
    const auto g = grey_step(30, 140, 170);
    ASSERT_TRUE(gc::find_grey_step_fast(g, 27.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
    EXPECT_NEAR(27.0 + off, 29.5, 0.6);
    // Either sign, from the other side.
    ASSERT_TRUE(gc::find_grey_step_fast(g, 33.0f, 10.0f, -1.0f, 0.0f, 8, 16, off));
    EXPECT_NEAR(33.0 - off, 29.5, 0.6);
    // A second, weaker step nearer the start does not win.
    cv::Mat1b two = g.clone();
    two.colRange(0, 25).setTo(125);
    ASSERT_TRUE(gc::find_grey_step_fast(two, 25.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
    EXPECT_NEAR(25.0 + off, 29.5, 0.6);
    // Below min_step (sensor noise, shading), or out of the window: nothing.
    EXPECT_FALSE(gc::find_grey_step_fast(grey_step(30, 160, 170), 27.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
    EXPECT_FALSE(gc::find_grey_step_fast(g, 45.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
    EXPECT_FALSE(gc::find_grey_step_fast(g, -100.0f, -100.0f, 1.0f, 0.0f, 8, 16, off));
}

// The hand (140) with the learnt scene behind it blanked from x = 30: the scene's border
// is an edge seen from the hand, never from inside the scene.
TEST(EdgeSearch, TakesTheSceneBorderOnlyWithTheSceneOutside)
{
    float off = 0;
    cv::Mat1b g(20, 60, uchar(140));
    g.colRange(30, 60).setTo(gc::kSceneGreyLevel);
    ASSERT_TRUE(gc::find_grey_step_fast(g, 27.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
    EXPECT_NEAR(27.0 + off, 29.5, 0.6);
    // From the scene outward (a contour lying inside the scene): passed over, although
    // the step is 140 levels. A weaker step in the hand beyond it is still found.
    EXPECT_FALSE(gc::find_grey_step_fast(g, 33.0f, 10.0f, -1.0f, 0.0f, 8, 16, off));
    g.colRange(0, 27).setTo(100);
    ASSERT_TRUE(gc::find_grey_step_fast(g, 33.0f, 10.0f, -1.0f, 0.0f, 8, 16, off));
    EXPECT_NEAR(33.0 - off, 26.5, 0.6);
    // The scene's own steps (a face's eyes and brows) are blanked with it: nothing there.
    EXPECT_FALSE(gc::find_grey_step_fast(g, 45.0f, 10.0f, 1.0f, 0.0f, 8, 16, off));
}

// A vertical boundary at x = edge between `skin` (left) and `wall` (right), each pixel the
// area-weighted mix of the two, then blurred like a lens.
cv::Mat3b colour_step(double edge, cv::Vec3b skin, cv::Vec3b wall)
{
    cv::Mat3b m(20, 60);
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) {
            const double cover = std::clamp(edge - x + 0.5, 0.0, 1.0);
            m(y, x) = cv::Vec3b(cv::Vec3d(skin) * cover + cv::Vec3d(wall) * (1.0 - cover));
        }
    cv::GaussianBlur(m, m, cv::Size(5, 5), 0.8);
    return m;
}

TEST(EdgeSearch, ColourEdgeIsWhereTheHandCoversHalfAPixel)
{
    const cv::Vec3b skin(90, 120, 190), wall(200, 205, 210);  // BGR: a light grey wall
    for (double edge : {30.0, 30.3, 30.6}) {
        const auto img = colour_step(edge, skin, wall);
        // A membership edge found 1.2 px inside the true one (as a skin model does against
        // a light background) is moved back to the boundary.
        const double found = edge - 1.2 - 28.0;
        const double off = gc::colour_edge_offset(img, {28.0, 10.0}, {1.0, 0.0}, found);
        EXPECT_NEAR(28.0 + off, edge, 0.1) << edge;
        // Searching leftward from the wall side (normal pointing into the wall, reversed
        // roles) finds the same boundary.
        const auto mirrored = colour_step(edge, wall, skin);
        const double off2 = gc::colour_edge_offset(mirrored, {28.0, 10.0}, {-1.0, 0.0}, 28.0 - edge - 1.0);
        EXPECT_NEAR(28.0 - off2, edge, 0.1) << edge;
    }
}

TEST(EdgeSearch, ColourEdgeKeepsTheOffsetWithoutContrastOrImage)
{
    const cv::Vec3b skin(90, 120, 190);
    const auto flat = colour_step(30.0, skin, cv::Vec3b(95, 124, 193));  // skin on skin
    EXPECT_DOUBLE_EQ(gc::colour_edge_offset(flat, {28.0, 10.0}, {1.0, 0.0}, 1.0), 1.0);
    EXPECT_DOUBLE_EQ(gc::colour_edge_offset(cv::Mat(), {28.0, 10.0}, {1.0, 0.0}, 1.0), 1.0);
    // Near and beyond the image border the samples are clamped, never read outside.
    const auto img = colour_step(30.0, skin, cv::Vec3b(200, 205, 210));
    EXPECT_TRUE(std::isfinite(gc::colour_edge_offset(img, {59.5, 19.5}, {1.0, 0.0}, 2.0)));
    EXPECT_TRUE(std::isfinite(gc::colour_edge_offset(img, {-5.0, -5.0}, {-1.0, 0.0}, 0.0)));
}

using gc_test::drawn_hand;

TEST(ContourMeasurement, MisfitIsLowestAtTheTrueState)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    const gc::ContourMeasurement meas;
    const gc::HandState truth{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    const double at_truth = meas.misfit(mask, t, truth);
    EXPECT_LT(at_truth, 0.02);
    for (const gc::HandState off :
         {gc::HandState{truth.x + 4, truth.y, 0, 1}, gc::HandState{truth.x, truth.y - 4, 0, 1},
          gc::HandState{truth.x, truth.y, 0.15, 1}, gc::HandState{truth.x, truth.y, 0, 1.12}})
        EXPECT_GT(meas.misfit(mask, t, off), at_truth + 0.03);
    // Nothing there at all: the cap.
    EXPECT_NEAR(meas.misfit(cv::Mat1b(mask.size(), uchar(0)), t, truth), 1.0, 1e-6);
    EXPECT_GT(meas.log_likelihood(0.01), meas.log_likelihood(0.1));
    EXPECT_NEAR(meas.normal_likelihood(0.0), 1.0, 1e-12);
    EXPECT_THROW(gc::ContourMeasurement(gc::ObservationParams{0, 2.0, 10.0}), std::invalid_argument);
}

// The hand in front of a skin-coloured patch that covers its right half: the plain misfit
// pays the cap where the edge vanishes, the judged misfit leaves those normals out and still
// tells the true state from a displaced one.
TEST(ContourMeasurement, JudgedMisfitLeavesOutSkinAgainstSkin)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    const gc::ContourMeasurement meas;
    const gc::HandState truth{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    double judged = 0.0;
    EXPECT_NEAR(meas.judged_misfit(mask, t, truth, judged), meas.misfit(mask, t, truth), 1e-4);
    EXPECT_NEAR(judged, 1.0, 1e-4);  // nothing is skin against skin

    cv::Mat1b covered = mask.clone();
    covered(cv::Rect(int(truth.x), 0, 320 - int(truth.x), 240)).setTo(255);
    const double plain = meas.misfit(covered, t, truth);
    const double at_truth = meas.judged_misfit(covered, t, truth, judged);
    EXPECT_GT(plain, 0.25);
    EXPECT_LT(at_truth, 0.05);
    EXPECT_GT(judged, 0.1);  // the palm's left half; the finger (weighted up) is covered
    EXPECT_LT(judged, 0.5);
    double judged_off = 0.0;
    EXPECT_GT(meas.judged_misfit(covered, t, {truth.x, truth.y - 5, 0, 1}, judged_off), at_truth + 0.1);
    EXPECT_GT(judged_off, 0.0);

    // All skin: nothing judges.
    EXPECT_NEAR(meas.judged_misfit(cv::Mat1b(mask.size(), uchar(255)), t, truth, judged), 1.0, 1e-12);
    EXPECT_EQ(judged, 0.0);
}

// The hand in front of a face that covers its right half, the hand's grey levels darker
// than the face's: with the grey map the covered normals measure the hand's outline again,
// so the true state scores as if nothing covered it and a displaced state scores worse.
TEST(ContourMeasurement, GreyStepsMeasureTheHandInFrontOfSkin)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    const gc::ContourMeasurement meas;
    const gc::HandState truth{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    cv::Mat1b covered = mask.clone();
    covered(cv::Rect(int(truth.x), 0, 320 - int(truth.x), 240)).setTo(255);
    cv::Mat1b grey(mask.size(), uchar(190));
    grey.setTo(150, mask);
    cv::GaussianBlur(grey, grey, cv::Size(5, 5), 0.8);

    const double plain = meas.misfit(covered, t, truth);
    const double at_truth = meas.misfit(covered, grey, t, truth);
    EXPECT_GT(plain, 0.25);
    EXPECT_LT(at_truth, 0.05);
    for (const gc::HandState off :
         {gc::HandState{truth.x + 4, truth.y, 0, 1}, gc::HandState{truth.x, truth.y - 4, 0, 1},
          gc::HandState{truth.x, truth.y, 0.15, 1}})
        EXPECT_GT(meas.misfit(covered, grey, t, off), at_truth + 0.03);
    // Where the skin edge is seen the grey map changes nothing.
    EXPECT_NEAR(meas.misfit(mask, grey, t, truth), meas.misfit(mask, t, truth), 1e-6);
    // A face of the hand's own grey level: no step, the plain misfit.
    EXPECT_NEAR(meas.misfit(covered, cv::Mat1b(mask.size(), uchar(150)), t, truth), plain, 1e-6);
    // Switched off, or a map of another size: not used.
    gc::ObservationParams off_params;
    off_params.min_grey_step = 0;
    EXPECT_NEAR(gc::ContourMeasurement(off_params).misfit(covered, grey, t, truth), plain, 1e-6);
    EXPECT_NEAR(meas.misfit(covered, cv::Mat1b(10, 10, uchar(0)), t, truth), plain, 1e-6);
    off_params.min_grey_step = 256;
    EXPECT_THROW(gc::ContourMeasurement{off_params}, std::invalid_argument);
}

TEST(ContourFit, RecoversAPerturbedState)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    // The same hand moved, turned and grown.
    const auto moved = drawn_hand({320, 240}, {158, 124}, 20.0 - 8.0, 1.08);
    const auto lm = gc::find_hand_landmarks(moved);
    const gc::HandState start{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    const auto fit = gc::refine_fit(moved, t, start, gc::FitParams{8, 8.0, 0.5, 2.0, 0.5});
    ASSERT_TRUE(fit.converged);
    EXPECT_NEAR(fit.state.scale, 1.08, 0.03);
    EXPECT_NEAR(fit.state.rotation, 8.0 * std::numbers::pi / 180.0, 0.03);  // clockwise on screen
    EXPECT_NEAR(fit.state.x, lm.palm.x, 2.5);
    EXPECT_NEAR(fit.state.y, lm.palm.y, 2.5);
    EXPECT_LT(fit.rms_px, 1.0);
    EXPECT_GT(fit.agreement, 0.9);
    // Nothing to fit: the start comes back, flagged.
    const auto none = gc::refine_fit(cv::Mat1b(mask.size(), uchar(0)), t, start);
    EXPECT_FALSE(none.converged);
    EXPECT_EQ(none.state.x, start.x);
}

TEST(ContourFit, AgreementFallsWhereTheTemplateHasNoEdgeInTheImage)
{
    // A template captured with a skin-coloured box merged into its palm, fitted to an image
    // where the hand has moved off the box: the box's side of the outline finds no edge.
    const auto hand = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    cv::Mat1b merged = hand.clone();
    cv::rectangle(merged, cv::Rect(110, 140, 45, 45), 255, cv::FILLED);
    const auto clean = gc::HandTemplate::from_mask(hand, hand);
    const auto with_box = gc::HandTemplate::from_mask(merged, merged);
    const gc::HandState at_clean{clean.origin_px.x, clean.origin_px.y, 0.0, 1.0};
    const gc::HandState at_box{with_box.origin_px.x, with_box.origin_px.y, 0.0, 1.0};
    const auto good = gc::refine_fit(hand, clean, at_clean);
    const auto bad = gc::refine_fit(hand, with_box, at_box);
    ASSERT_TRUE(good.converged);
    EXPECT_GT(good.agreement, 0.9);
    EXPECT_LT(bad.agreement, good.agreement - 0.15);
}

// Placed by a squashed state, the normals stay unit, perpendicular to the placed outline's
// tangents (the inverse transpose of the placement's linear part), and outward.
TEST(ContourMeasurement, SquashedNormalsArePerpendicularToTheSquashedOutline)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    const gc::HandState s{t.origin_px.x, t.origin_px.y, 0.4, 1.1, 0.7};
    const std::size_t n = t.outline.size();
    std::vector<cv::Point2f> placed(n);
    for (std::size_t k = 0; k < n; ++k) placed[k] = cv::Point2f(gc::place(s, t.outline[k]));
    int inward = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // The template's tangent at the point, placed as a displacement of it.
        const cv::Point2f& u = t.outline[i];
        const cv::Point2f along(-t.outline_normals[i].y, t.outline_normals[i].x);
        const cv::Point2d tangent = gc::place(s, u + along) - gc::place(s, u);
        const cv::Point2d nrm = gc::place_normal(s, t.outline_normals[i]);
        EXPECT_NEAR(std::hypot(nrm.x, nrm.y), 1.0, 1e-9);
        EXPECT_NEAR(nrm.dot(tangent), 0.0, 1e-5) << i;  // float template points
        // Outward: a step along the normal leaves the placed outline's interior.
        const cv::Point2d step = cv::Point2d(placed[i]) + 2.0 * nrm;
        inward += cv::pointPolygonTest(placed, cv::Point2f(step), false) > 0.0;
    }
    EXPECT_EQ(inward, 0);
}

// Unsquashed, the placement rounds exactly as the similarity it was before the squash.
TEST(ContourMeasurement, UnsquashedPlacementIsTheSimilarityExactly)
{
    const gc::HandState s{123.4, -56.7, 0.73, 1.37};
    const double c = std::cos(s.rotation) * s.scale, sn = std::sin(s.rotation) * s.scale;
    for (const cv::Point2f u : {cv::Point2f(3.1f, -7.9f), cv::Point2f(-41.3f, 12.7f), cv::Point2f(0.1f, 55.5f)}) {
        const cv::Point2d p = gc::place(s, u);
        EXPECT_EQ(p.x, s.x + c * u.x - sn * u.y);
        EXPECT_EQ(p.y, s.y + sn * u.x + c * u.y);
    }
}

// The hand turned about the vertical axis narrows in the image: fitting the squash follows
// it over a few frames (each call moves it by at most max_squash_step) and fits the outline
// better than the similarity alone can.
TEST(ContourFit, FollowsAHorizontalSquash)
{
    const auto mask = drawn_hand({320, 240}, {150, 130}, 20.0, 1.0);
    const auto t = gc::HandTemplate::from_mask(mask, mask);
    // The same hand narrowed to 0.85 of its width about the palm.
    const cv::Matx23d narrow(0.85, 0.0, (1.0 - 0.85) * t.origin_px.x, 0.0, 1.0, 0.0);
    cv::Mat1b turned;
    cv::warpAffine(mask, turned, narrow, mask.size(), cv::INTER_LINEAR);
    const gc::HandState start{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    gc::FitParams params;
    params.fit_squash = true;
    gc::HandState s = start;
    gc::FitResult fit;
    for (int frame = 0; frame < 8; ++frame) {
        fit = gc::refine_fit(turned, t, s, params);
        ASSERT_TRUE(fit.converged);
        EXPECT_GE(fit.state.squash, s.squash * (1.0 - params.max_squash_step) - 1e-12);
        s = fit.state;
    }
    EXPECT_NEAR(s.squash, 0.85, 0.03);
    EXPECT_NEAR(s.scale, 1.0, 0.04);
    EXPECT_NEAR(s.rotation, 0.0, 0.03);
    const auto rigid = gc::refine_fit(turned, t, start);
    ASSERT_TRUE(rigid.converged);
    EXPECT_EQ(rigid.state.squash, 1.0);
    EXPECT_GT(fit.agreement, rigid.agreement + 0.1);
    EXPECT_LT(fit.rms_px, rigid.rms_px);
    // The particles are weighted with the squash too (the measurement's own placement).
    const gc::ContourMeasurement meas;
    EXPECT_LT(meas.misfit(turned, t, s), 0.5 * meas.misfit(turned, t, rigid.state));
    // On the unturned hand the squash stays near 1.
    const auto same = gc::refine_fit(mask, t, start, params);
    EXPECT_NEAR(same.state.squash, 1.0, 0.01);
    // A squash the placement cannot divide by is refused, by the fit and the measurement.
    for (const double bad :
         {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
        gc::HandState s_bad = start;
        s_bad.squash = bad;
        EXPECT_THROW(gc::refine_fit(turned, t, s_bad, params), std::invalid_argument) << bad;
        EXPECT_THROW(gc::ContourMeasurement().misfit(turned, t, s_bad), std::invalid_argument) << bad;
    }
}

}  // namespace
