// One CONDENSATION iteration of a tracked hand (the thesis's loop): resample, predict with
// the camera's motion, weigh by the observation density, estimate; then the judgement of
// whether the hand is still under the estimate.
#include "tracker/hand_tracker_impl.hpp"

#include "filter/resampling.hpp"
#include "measure/contour_fit.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc {

namespace {

constexpr double kAdaptConfidence = 0.8;  // skin mean adapts only from a trusted contour
constexpr double kMinJudgedWeight = 0.3;  // share of the normals that must see an edge to judge

double wrap_angle(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

}  // namespace

void HandTracker::Impl::track(const cv::Mat& bgr, const ImageMotion& motion)
{
    const Spread spread = predict(motion);
    // Every hypothesis outside the frame (the head turned far): nothing to measure.
    if (!map_skin(bgr, spread)) {
        lose();
        return;
    }
    // While the edges are weak the hand is likely in front of skin (a face, a skin-coloured
    // object), and the normals from skin into skin are measured on the grey levels.
    // Elsewhere such normals are few and the skin edges decide alone, which spares the grey
    // map's cost on most frames. Not with a template that is not even pointing-shaped: its
    // outline is not the hand's silhouette, and inside a face grey steps (eyes, brows,
    // mouth) are everywhere for it to settle on.
    const bool use_steps = edges_were_weak && template_quality != CaptureQuality::Unsure;
    const cv::Mat1b& steps = use_steps ? grey : no_map;
    if (use_steps) update_steps(bgr, membership_roi);
    const Weighed w = weigh_and_judge(steps, use_steps);

    // Refine from the better of mean and best; report that. The squash follows the hand's
    // turn only while its edges fit (where they are weak, in front of a face, the outline's
    // horizontal extent is not seen), and only for a clean template: one merged with
    // something else would use it to stretch over that.
    const double mean_misfit = measurement.misfit(membership, steps, *shape, w.mean);
    const HandState start = mean_misfit <= w.best_misfit ? w.mean : w.best;
    FitParams refine;
    refine.fit_squash = !w.weak_edges && template_quality == CaptureQuality::Clean;
    const FitResult fit = refine_fit(membership, *shape, start, refine, bgr);
    const HandState out = fit.converged ? fit.state : start;

    // Lost when the edges no longer fit (thesis: every likelihood < lost_ratio x P_init),
    // not even the refined contour's, and the contour's inner rim is no longer skin. Edges
    // also vanish where the hand passes in front of a face or a skin-coloured object; there
    // the hand is still under the contour, and tracking goes on while the rim is skin,
    // while the edges that can still be seen (not skin against skin) fit as well as
    // tracking did, or while the contour outlines something that moved in front of the
    // learnt scene. The refined contour is the best placed one to judge.
    if (w.weak_edges && !hand_still_there(out, steps, bgr)) {
        if (++low_frames >= params.lost_frames) {
            lose();
            return;
        }
    } else {
        low_frames = 0;
    }
    if (settle_trial(bgr, out, fit.converged ? fit.agreement : 0.0, w.weak_edges)) return;
    follow(bgr, out, motion, w.weak_edges);
}

// The skin map once per frame, over the region the hypotheses can reach; the rest of the
// map stays 0 (cleared where the previous region was). False when that region is empty.
bool HandTracker::Impl::map_skin(const cv::Mat& bgr, const Spread& spread)
{
    const double reach =
        spread.max_scale * std::max(1.0, previous.squash) * template_radius + measurement.params().half_window + 2.0;
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    const cv::Rect roi =
        cv::Rect(cv::Point(int(std::floor(spread.min_x - reach)), int(std::floor(spread.min_y - reach))),
                 cv::Point(int(std::ceil(spread.max_x + reach)) + 1, int(std::ceil(spread.max_y + reach)) + 1)) &
        frame;
    if (membership_roi.area() > 0) membership(membership_roi).setTo(0);
    membership_roi = roi;
    if (roi.area() == 0) return false;
    skin->membership(bgr, roi, membership);
    return true;
}

// Weighs the particles, records the estimate's mean, best and confidence (against P_init,
// taken on the first frame of a track), and judges whether the edges are weak.
HandTracker::Impl::Weighed HandTracker::Impl::weigh_and_judge(const cv::Mat1b& steps, bool use_steps)
{
    Weighed w;
    w.best_misfit = 2.0;
    const std::size_t best = weigh(steps, w.best_misfit);
    w.best = particles[best].state;
    w.mean = weighted_mean(w.best);
    estimate.mean = w.mean;
    estimate.best = w.best;

    const double best_like = measurement.normal_likelihood(w.best_misfit);
    if (awaiting_p_init) {
        p_init = best_like;
        awaiting_p_init = false;
    }
    estimate.confidence = p_init > 0.0 ? std::clamp(best_like / p_init, 0.0, 1.0) : 0.0;
    w.weak_edges = best_like < params.lost_ratio * p_init;
    // Whether the next frame measures grey steps is judged on the skin edges alone: judged
    // with the steps, finding them would switch them off on the next frame and the density
    // would alternate between two landscapes, frame by frame.
    edges_were_weak = use_steps
                          ? measurement.normal_likelihood(measurement.misfit(membership, no_map, *shape, w.best)) <
                                params.lost_ratio * p_init
                          : w.weak_edges;
    return w;
}

// While the edges are weak the hand may be touching a face or a skin-coloured object, and a
// capture now could merge it: a candidate larger than the tracked hand waits for a frame
// where the hand stands apart. A smaller one may still drop what a merged template holds,
// but not by a verdict taken on such a frame, where part of either outline may be unseen.
// The area the edges last fitted can itself be wrong (a contour shrunk onto a piece of the
// hand still fits edges there), so a candidate is stepped on at least one frame first, and
// one whose outline has agreed with the image clearly better than the tracked one's on
// every frame so far is not dropped for its size. True when the candidate took over.
bool HandTracker::Impl::settle_trial(const cv::Mat& bgr, const HandState& out, double agreement, bool weak_edges)
{
    if (weak_edges && trial && trial->frames() > 0 && !trial->clearly_better() &&
        grows_hand(cv::contourArea(trial->candidate().outline) * trial->state().scale * trial->state().scale))
        trial.reset();
    return trial && try_template(bgr, out, agreement, !weak_edges);
}

// Resample (systematic, O(N)), then predict through the zero-order dynamics plus the
// camera-motion offset, with quasi-random noise. Returns the predicted set's extent.
HandTracker::Impl::Spread HandTracker::Impl::predict(const ImageMotion& motion)
{
    const std::size_t n = particles.size();
    for (std::size_t i = 0; i < n; ++i) weights[i] = particles[i].weight;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    systematic_resample(weights, unit(rng), ancestors);
    sampler.next_frame(deviates);
    const NoiseVector& sd = noise.sigma();
    Spread spread{1e300, 1e300, -1e300, -1e300, 0.0};
    for (std::size_t i = 0; i < n; ++i) {
        HandState s = particles[ancestors[i]].state;
        const double* w = &deviates[4 * i];
        s.x += motion.dx + sd[0] * w[0];
        s.y += motion.dy + sd[1] * w[1];
        s.rotation += motion.drotation + sd[2] * w[2];
        s.scale = std::clamp(s.scale * motion.scale_factor * std::exp(sd[3] * w[3]), tracking::kMinScale,
                             tracking::kMaxScale);
        s.squash = previous.squash;  // the shape, not a sampled dimension
        predicted[i].state = s;
        spread.min_x = std::min(spread.min_x, s.x);
        spread.max_x = std::max(spread.max_x, s.x);
        spread.min_y = std::min(spread.min_y, s.y);
        spread.max_y = std::max(spread.max_y, s.y);
        spread.max_scale = std::max(spread.max_scale, s.scale);
    }
    std::swap(particles, predicted);
    return spread;
}

// Weights every particle by the observation density; returns the best one's index and
// its misfit in `best_misfit` (which enters holding the largest misfit worth measuring).
std::size_t HandTracker::Impl::weigh(const cv::Mat1b& steps, double& best_misfit)
{
    const std::size_t n = particles.size();
    std::size_t best = 0;
    const double margin = measurement.negligible_margin();
    for (std::size_t i = 0; i < n; ++i) {
        const double q = measurement.misfit(membership, steps, *shape, particles[i].state, best_misfit + margin);
        log_weights[i] = measurement.log_likelihood(q);
        if (q < best_misfit) {
            best_misfit = q;
            best = i;
        }
    }
    normalise_log_weights(log_weights);
    for (std::size_t i = 0; i < n; ++i) particles[i].weight = log_weights[i];
    return best;
}

// The weighted mean state: rotation averaged about the best one, scale geometrically.
HandState HandTracker::Impl::weighted_mean(const HandState& best) const
{
    HandState mean{0.0, 0.0, 0.0, 0.0};
    double log_s = 0.0;
    for (const Particle& p : particles) {
        mean.x += p.weight * p.state.x;
        mean.y += p.weight * p.state.y;
        mean.rotation += p.weight * wrap_angle(p.state.rotation - best.rotation);
        log_s += p.weight * std::log(p.state.scale);
    }
    mean.rotation += best.rotation;
    mean.scale = std::exp(log_s);
    mean.squash = previous.squash;
    return mean;
}

// On a weak-edge frame: whether the contour at `s` still holds the hand (see track()).
bool HandTracker::Impl::hand_still_there(const HandState& s, const cv::Mat1b& steps, const cv::Mat& bgr) const
{
    const double like = measurement.normal_likelihood(measurement.misfit(membership, steps, *shape, s));
    if (like >= params.lost_ratio * p_init) return true;
    const RimSurvey rim = survey_rim(*shape, s, membership, known_scene(), bgr);
    return rim_is_skin(rim) || visible_edges_fit(s) || outlines_foreground(rim);
}

// True when the normals that are not skin against skin carry enough of the weight and fit
// them as well as tracking did (lost_ratio x P_init).
bool HandTracker::Impl::visible_edges_fit(const HandState& s) const
{
    double judged = 0.0;
    const double q = measurement.judged_misfit(membership, *shape, s, judged);
    return judged >= kMinJudgedWeight && measurement.normal_likelihood(q) >= params.lost_ratio * p_init;
}

// Takes `out` as this frame's state: the noise adapts to the motion seen, the estimate is
// reported, and the skin model and the template's custody follow.
void HandTracker::Impl::follow(const cv::Mat& bgr, const HandState& out, const ImageMotion& motion, bool weak_edges)
{
    noise.update({out.x - previous.x - motion.dx, out.y - previous.y - motion.dy,
                  wrap_angle(out.rotation - previous.rotation - motion.drotation),
                  std::log(out.scale / (previous.scale * motion.scale_factor))});
    previous = out;
    report(out);
    if (!weak_edges) firm_area = std::abs(cv::contourArea(estimate.contour));
    if (params.adapt_skin && estimate.confidence >= kAdaptConfidence) adapt_skin(bgr);
    ++tracked_frames;
    if (template_quality != CaptureQuality::Clean) recapture(bgr, weak_edges);
}

}  // namespace gc
