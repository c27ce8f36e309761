#include "contour/hand_template.hpp"
#include "measure/contour_fit.hpp"
#include "tracker/template_trial.hpp"

#include "drawn_hand.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>

namespace {

using gc_test::drawn_hand;

const cv::Size kSize{320, 240};
const cv::Rect kBox{110, 140, 45, 45};  // a static skin-coloured box behind the palm

// The hand's palm in frame k: it moves up and right, off the box.
cv::Point2d palm_at(int k) { return {150.0 + 4.0 * k, 130.0 - 3.0 * k}; }

cv::Mat1b skin_map(int k)
{
    cv::Mat1b m = drawn_hand(kSize, palm_at(k), 20.0, 1.0);
    cv::rectangle(m, kBox, 255, cv::FILLED);
    return m;
}

gc::HandState at(const gc::HandTemplate& t, int k)
{
    const cv::Point2d d = palm_at(k) - palm_at(0);
    return {t.origin_px.x + d.x, t.origin_px.y + d.y, 0.0, 1.0};
}

// Runs a trial of `candidate` beside `tracked` (both captured in frame 0) while the hand
// moves off the box; the tracked template follows the hand exactly, as a filter would.
gc::TemplateTrial::Verdict run_trial(const gc::HandTemplate& tracked, const gc::HandTemplate& candidate,
                                     gc::HandState* final_state)
{
    gc::TemplateTrial trial(candidate, gc::SkinModel::generic(), at(candidate, 0));
    auto verdict = gc::TemplateTrial::Verdict::Running;
    for (int k = 1; verdict == gc::TemplateTrial::Verdict::Running; ++k) {
        const cv::Mat1b memb = skin_map(k);
        const auto fit = gc::refine_fit(memb, tracked, at(tracked, k));
        verdict = trial.step(memb, {}, at(tracked, k - 1), fit.state, fit.agreement);
        EXPECT_LE(k, gc::TemplateTrial::kFrames);
    }
    if (final_state) *final_state = trial.state();
    return verdict;
}

TEST(TemplateTrial, MovedAlongAppliesTheSameSimilarityMotion)
{
    const gc::HandState from{100, 100, 0.0, 1.0}, to{110, 95, std::numbers::pi / 2, 2.0};
    // A point 10 px right of `from` ends 20 px below `to` (turned a quarter, doubled).
    const auto s = gc::moved_along({110, 100, 0.3, 1.5}, from, to);
    EXPECT_NEAR(s.x, 110.0, 1e-9);
    EXPECT_NEAR(s.y, 115.0, 1e-9);
    EXPECT_NEAR(s.rotation, 0.3 + std::numbers::pi / 2, 1e-9);
    EXPECT_NEAR(s.scale, 3.0, 1e-9);
}

TEST(TemplateTrial, ACaptureOfTheHandAloneReplacesOneMergedWithAStaticObject)
{
    const cv::Mat1b first = skin_map(0);
    const auto merged = gc::HandTemplate::from_mask(first, first);
    const cv::Mat1b hand = drawn_hand(kSize, palm_at(0), 20.0, 1.0);
    const auto alone = gc::HandTemplate::from_mask(hand, first);
    gc::HandState end;
    EXPECT_EQ(run_trial(merged, alone, &end), gc::TemplateTrial::Verdict::Replaced);
    // The winner has followed the hand: its palm is where the hand is now.
    const auto last = at(alone, gc::TemplateTrial::kFrames);
    EXPECT_NEAR(end.x, last.x, 1.5);
    EXPECT_NEAR(end.y, last.y, 1.5);
    // The other way round the template stays.
    EXPECT_EQ(run_trial(alone, merged, nullptr), gc::TemplateTrial::Verdict::Kept);
    // And two captures of the same hand: no reason to change.
    EXPECT_EQ(run_trial(alone, alone, nullptr), gc::TemplateTrial::Verdict::Kept);
}

// Whether, after the frames before the verdict, the candidate has clearly out-agreed the
// tracked template (TemplateTrial::clearly_better); the tracked one is placed at
// `tracked_scale` about its palm, as a filter whose scale collapsed would place it.
bool clearly_better_before_verdict(const gc::HandTemplate& tracked, double tracked_scale,
                                   const gc::HandTemplate& candidate)
{
    const auto placed = [&](int k) {
        gc::HandState s = at(tracked, k);
        s.scale = tracked_scale;
        return s;
    };
    gc::TemplateTrial trial(candidate, gc::SkinModel::generic(), at(candidate, 0));
    EXPECT_FALSE(trial.clearly_better());  // no evidence yet
    for (int k = 1; k < gc::TemplateTrial::kFrames; ++k) {
        const cv::Mat1b memb = skin_map(k);
        const auto fit = gc::refine_fit(memb, tracked, placed(k));
        EXPECT_EQ(trial.step(memb, {}, placed(k - 1), placed(k), fit.converged ? fit.agreement : 0.0),
                  gc::TemplateTrial::Verdict::Running);
    }
    EXPECT_EQ(trial.frames(), gc::TemplateTrial::kFrames - 1);
    return trial.clearly_better();
}

TEST(TemplateTrial, TheWholeHandClearlyOutAgreesAContourShrunkOntoPartOfIt)
{
    const cv::Mat1b first = skin_map(0);
    const auto alone = gc::HandTemplate::from_mask(drawn_hand(kSize, palm_at(0), 20.0, 1.0), first);
    EXPECT_TRUE(clearly_better_before_verdict(alone, 0.5, alone));
    // Not the other way round, nor between two contours that both fit.
    EXPECT_FALSE(clearly_better_before_verdict(alone, 1.0, alone));
    const auto merged = gc::HandTemplate::from_mask(first, first);
    EXPECT_FALSE(clearly_better_before_verdict(alone, 1.0, merged));
}

}  // namespace
