#include "tracker/hand_tracker.hpp"

#include "background/static_background.hpp"
#include "contour/hand_template.hpp"
#include "detect/motion_detector.hpp"
#include "filter/adaptive_noise.hpp"
#include "filter/quasi_random.hpp"
#include "filter/resampling.hpp"
#include "measure/contour_fit.hpp"
#include "measure/contour_measurement.hpp"
#include "measure/edge_search.hpp"
#include "skin/skin_model.hpp"
#include "tracker/template_trial.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

// Scale is relative to the template: a hand does not halve or double its distance while
// tracked, and tiny hypotheses would otherwise fit any small skin blob.
constexpr double kMinScale = 0.5;
constexpr double kMaxScale = 2.0;
constexpr double kAdaptConfidence = 0.8;  // skin mean adapts only from a trusted contour
constexpr double kAdaptRate = 0.05;
constexpr int kMinFrameSide = 32;
constexpr double kRimSkinFraction = 0.85;       // inner rim this much skin: the hand is there;
constexpr double kLooseRimSkinFraction = 0.75;  // ... or this much, with the finger's at 0.85
constexpr double kRimDepth = 2.5;           // px along the normals, in or out: the contour's rims
constexpr double kForegroundRimSkinFraction = 0.5;  // a contour on what moved: this much rim skin,
constexpr double kMovedFraction = 0.5;               // this much of it known to differ from the scene,
constexpr double kMaxSceneInsideFraction = 0.15;    // at most this much of it the scene,
constexpr double kSceneOutsideFraction = 0.5;        // and this much of the outer rim matching it
// Inner rim share of the static scene above which a contour holds some of it: a hand
// alone shows 0.13 or less on 99 % of frames (face_pass 1-200), a merged template 0.14 at median.
constexpr double kMergedSceneFraction = 0.15;
// ... and above which it lies on the scene rather than on the hand: 4 of 37 855 frames on
// the hand (IoU >= 0.85), 76 of the 146 below IoU 0.3 (face_pass 1-200).
constexpr double kOnSceneFraction = 0.5;
constexpr double kMinJudgedWeight = 0.3;   // share of the normals that must see an edge to judge
constexpr double kMaxCaptureGrowth = 1.15;  // area ratio: a capture this much larger adds something
constexpr int kLostSearchEvery = 3;
constexpr int kRecapturePeriod = 16;  // while the template is provisional, look again this often
constexpr int kUnsureRecapturePeriod = 8;  // ... and this often while it is not even pointing-shaped
constexpr int kRecaptureFrames = 7;   // ... over this many frames (history_frames + 1)
constexpr double kStillMotion = 0.02;  // moved share of the contour below which it held still

void check_frame(const cv::Mat& bgr) {
    if (bgr.empty()) throw std::invalid_argument("HandTracker: empty frame");
    if (bgr.type() != CV_8UC3)
        throw std::invalid_argument("HandTracker: expected a CV_8UC3 (BGR) frame, got " +
                                    std::to_string(bgr.channels()) + " channel(s) of depth " +
                                    std::to_string(bgr.depth()));
    if (bgr.cols < kMinFrameSide || bgr.rows < kMinFrameSide)
        throw std::invalid_argument("HandTracker: frame " + std::to_string(bgr.cols) + "x" +
                                    std::to_string(bgr.rows) + " is smaller than 32x32");
}

void check_params(const TrackerParams& p) {
    if (p.particles < 1) throw std::invalid_argument("HandTracker: particles must be >= 1");
    if (p.particles > 1'000'000)
        throw std::invalid_argument("HandTracker: particles must be <= 1000000");
    if (!(p.lost_ratio > 0.0 && p.lost_ratio < 1.0))
        throw std::invalid_argument("HandTracker: lost_ratio must be in (0, 1)");
    if (p.lost_frames < 1) throw std::invalid_argument("HandTracker: lost_frames must be >= 1");
}

void check_motion(const ImageMotion& m) {
    if (!std::isfinite(m.dx) || !std::isfinite(m.dy) || !std::isfinite(m.drotation) ||
        !(m.scale_factor > 0.0) || !std::isfinite(m.scale_factor))
        throw std::invalid_argument("HandTracker: camera motion must be finite with scale_factor > 0");
}

double wrap_angle(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

}  // namespace

struct HandTracker::Impl {
    TrackerParams params;
    ContourMeasurement measurement;
    AdaptiveNoise noise;
    QuasiNormalSampler sampler;
    std::mt19937_64 rng;
    MotionDetector detector;
    StaticBackground background;

    std::optional<SkinModel> skin;
    std::optional<HandTemplate> shape;
    double template_radius = 0.0;  // largest |u| of the outline, at scale 1
    int template_side = 0;         // larger side of the outline's box, at scale 1

    std::vector<Particle> particles, predicted;
    std::vector<double> log_weights, weights, deviates;
    std::vector<std::uint32_t> ancestors;
    cv::Mat1b membership;
    cv::Rect membership_roi;
    cv::Mat1b grey;  // the frame's grey levels, where the membership map was computed
    const cv::Mat1b no_map;  // an empty map: no grey steps, no static scene
    bool edges_were_weak = false;  // on the last tracked frame (best_like < lost_ratio P_init)
    cv::Mat1b contour_fill;
    std::vector<cv::Point> fill_points;

    EyeEstimate estimate;
    cv::Size frame_size;
    double p_init = 0.0;           // per-normal likelihood of the first tracked iteration
    bool awaiting_p_init = false;
    int low_frames = 0;
    HandState previous;            // the last reported (refined) state
    CaptureQuality template_quality = CaptureQuality::Unsure;  // of the template's capture
    int tracked_frames = 0;        // since the last start_tracking
    double firm_area = 0.0;        // of the contour, on the last frame whose edges fitted
    int lost_search = 0;           // frames searched since the hand was lost
    cv::Rect recapture_roi;        // the window the detector watches while tracking
    bool watch_everywhere = false; // the last watch saw the tracked contour hold still

    std::optional<TemplateTrial> trial;  // a re-capture of the template's quality, on trial

    explicit Impl(const TrackerParams& p)
        : params(p), sampler(4, p.seed ^ 0x5EEDULL), rng(p.seed) {
        check_params(p);
        particles.resize(p.particles);
        predicted.resize(p.particles);
        log_weights.resize(p.particles);
        weights.resize(p.particles);
        deviates.resize(4 * static_cast<std::size_t>(p.particles));
        ancestors.resize(p.particles);
    }

    // Back to the state of a fresh tracker, random streams included: a reset tracker gives
    // the same output as a new one with the same parameters.
    void reset() {
        sampler = QuasiNormalSampler(4, params.seed ^ 0x5EEDULL);
        rng.seed(params.seed);
        template_radius = 0.0;
        template_side = 0;
        previous = HandState{};
        membership_roi = {};
        detector.reset();
        background.reset();
        noise.reset();
        skin.reset();
        shape.reset();
        estimate = EyeEstimate{};
        frame_size = {};
        membership.release();
        grey.release();
        edges_were_weak = false;
        p_init = 0.0;
        awaiting_p_init = false;
        low_frames = 0;
        template_quality = CaptureQuality::Unsure;
        tracked_frames = 0;
        firm_area = 0.0;
        lost_search = 0;
        recapture_roi = {};
        watch_everywhere = false;
        trial.reset();
        for (auto& p : particles) p = Particle{};
    }

    const EyeEstimate& process(const cv::Mat& bgr, const ImageMotion& motion) {
        check_frame(bgr);
        check_motion(motion);
        if (frame_size.area() > 0 && bgr.size() != frame_size)
            throw std::invalid_argument(
                "HandTracker: frame size changed from " + std::to_string(frame_size.width) + "x" +
                std::to_string(frame_size.height) + " to " + std::to_string(bgr.cols) + "x" +
                std::to_string(bgr.rows) + " without reset()");
        frame_size = bgr.size();
        if (membership.size() != frame_size) {
            membership = cv::Mat1b(frame_size, uchar(0));
            membership_roi = {};
        }
        // A turn of the head moves the scene in the image: its median starts again.
        if (motion.dx != 0.0 || motion.dy != 0.0 || motion.drotation != 0.0 ||
            motion.scale_factor != 1.0)
            background.reset();
        if (estimate.state == TrackState::Tracking) {
            track(bgr, motion);
        } else {
            acquire(bgr);
        }
        if (params.use_static_scene) learn_background(bgr);
        return estimate;
    }

    // --- acquisition -------------------------------------------------------------------

    void acquire(const cv::Mat& bgr) {
        // A known hand that was lost may return without waving: look for it by skin first.
        // While lost, the whole-frame searches are the expensive part of a frame: the skin
        // search runs every kLostSearchEvery frames and the motion detection segments every
        // other frame (it still differences every frame, so no motion is missed).
        const bool lost = estimate.state == TrackState::Lost;
        const int turn = lost ? lost_search++ : 0;
        if (lost && shape && skin && turn % kLostSearchEvery == 0 && reacquire_by_skin(bgr)) return;
        const SkinModel prior = skin ? *skin : SkinModel::generic();
        const bool segment = !lost || turn % 2 == 1;
        const auto found = detector.process(bgr, prior, segment, static_scene(bgr, segment, {}));
        if (!found) return;
        // A template is only captured from a hand wholly in view: a shape cut by the image
        // border would be tracked as that cut shape from then on.
        const cv::Rect box = cv::boundingRect(found->mask);
        if (box.x <= 1 || box.y <= 1 || box.br().x >= bgr.cols - 1 || box.br().y >= bgr.rows - 1)
            return;
        cv::Mat1b memb(bgr.size(), uchar(0));
        found->skin.membership(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), memb);
        // The hand seen before is kept when it fits the detection: a new capture could
        // include skin-coloured things the hand touches at this moment. Unless the known
        // template was itself unsure and this capture is clean.
        const CaptureQuality quality = capture_quality(*found);
        const bool cleaner = template_quality != CaptureQuality::Clean && quality == CaptureQuality::Clean;
        if (shape && skin && !cleaner && refit_known_shape(*found, memb, bgr)) return;
        capture(*found, quality, memb, bgr);
    }

    // A new template from a detection; false (nothing changed) if the blob has no finger.
    bool capture(const Detection& found, CaptureQuality quality, const cv::Mat1b& memb,
                 const cv::Mat& bgr) {
        auto captured = template_from(found, memb, bgr);
        if (!captured) return false;
        const HandState at = as_captured(*captured);
        adopt(std::move(*captured), found.skin, quality, at);
        return true;
    }

    // A template's state in the frame it was captured from.
    static HandState as_captured(const HandTemplate& t) {
        return HandState{t.origin_px.x, t.origin_px.y, 0.0, 1.0};
    }

    static std::optional<HandTemplate> template_from(const Detection& found, const cv::Mat1b& memb,
                                                     const cv::Mat& bgr) {
        try {
            return HandTemplate::from_mask(found.mask, memb, TemplateOptions{}, bgr, found.motion);
        } catch (const std::invalid_argument&) {
            return std::nullopt;  // a moving blob without a finger: keep waiting
        }
    }

    void adopt(HandTemplate&& t, const SkinModel& model, CaptureQuality quality, const HandState& at) {
        shape = std::move(t);
        skin = model;
        template_radius = 0.0;
        for (const auto& p : shape->outline)
            template_radius = std::max(template_radius, double(std::hypot(p.x, p.y)));
        const cv::Rect extent = cv::boundingRect(shape->outline);
        template_side = std::max(extent.width, extent.height);
        start_tracking(at);
        template_quality = quality;
        report(at);
    }

    // While the template is not clean, the detector looks again now and then: every
    // kRecapturePeriod frames it watches kRecaptureFrames consecutive frames of a window
    // around the tracked hand (three times its box, the box at least as large as the
    // template's larger side, so that a contour shrunk onto a sliver of the hand still
    // watches a window the hand fits in: a fraction of the frame's cost) and segments the
    // last one. A capture of better quality (clean over pointing-shaped over
    // neither) of a hand wholly inside the window, overlapping the tracked one, replaces the
    // template; while the edges are weak (`weak_edges`), only one no larger than the hand.
    // The hand is what waved: a watch that saw (nearly) nothing change under the tracked
    // contour says it may hold a static skin-coloured object instead (a template merged
    // with one at capture, left on it as the hand moved off). The next watch then covers
    // the whole frame, and there a capture need not overlap the tracked contour. So does
    // the learnt scene, at once: a tracked contour whose inner rim is mostly the scene is
    // replaced by any capture of its rank in the window.
    bool recapture(const cv::Mat& bgr, bool weak_edges) {
        const int period = template_quality == CaptureQuality::Unsure || watch_everywhere
                               ? kUnsureRecapturePeriod
                               : kRecapturePeriod;
        const int phase = tracked_frames % period;
        const int first = period - kRecaptureFrames;
        if (phase < first) return false;
        const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
        if (phase == first) {
            const cv::Rect b = at_least(estimate.bbox, template_side);
            recapture_roi = watch_everywhere
                                ? frame
                                : cv::Rect(b.x - b.width, b.y - b.height, 3 * b.width, 3 * b.height) & frame;
            detector.reset();
        }
        if (recapture_roi.width < 32 || recapture_roi.height < 32) return false;
        const bool last = phase == period - 1;
        const cv::Mat1b& scene = static_scene(bgr, last, recapture_roi);
        const auto found =
            detector.process(bgr(recapture_roi), *skin, last, scene.empty() ? scene : scene(recapture_roi));
        const bool everywhere = recapture_roi == frame && watch_everywhere;
        if (last) {
            watch_everywhere = contour_held_still(detector.recent_motion(), recapture_roi);
            detector.reset();
        }
        // Two watches in a row saw the contour hold still while this hand moved elsewhere:
        // the contour is on something static, and a capture of its rank away from it
        // replaces it without a trial (which would move it with the static contour).
        const bool still_twice = everywhere && watch_everywhere;
        if (!found) return false;
        const CaptureQuality quality = capture_quality(*found);
        if (quality < template_quality) return false;
        if (weak_edges && grows_hand(found->area)) return false;
        const cv::Rect local = cv::boundingRect(found->mask);
        const bool apart = ((local + recapture_roi.tl()) & estimate.bbox).area() == 0;
        // A contour whose inner rim is mostly the learnt scene has been left on a static
        // thing (a template merged with it, the hand gone on): a capture of its rank
        // replaces it without a trial, wherever it is in the window.
        const bool on_scene = lies_on_scene(previous, bgr);
        const bool equal = quality == template_quality && !(still_twice && apart) && !on_scene;
        if (equal && trial) return false;
        if (local.x <= 1 || local.y <= 1 || local.br().x >= recapture_roi.width - 1 ||
            local.br().y >= recapture_roi.height - 1)
            return false;  // cut by the window (or the frame): not the whole hand
        if (!everywhere && apart && !on_scene) return false;
        Detection whole = *found;
        whole.mask = cv::Mat1b(bgr.size(), uchar(0));
        found->mask.copyTo(whole.mask(recapture_roi));
        whole.motion = cv::Mat1b(bgr.size(), uchar(0));
        if (!found->motion.empty()) found->motion.copyTo(whole.motion(recapture_roi));
        cv::Mat1b memb(bgr.size(), uchar(0));
        found->skin.membership(bgr, recapture_roi, memb);
        if (equal) {
            auto candidate = template_from(whole, memb, bgr);
            if (!candidate) return false;
            const HandState at = as_captured(*candidate);
            trial.emplace(std::move(*candidate), whole.skin, at);
            return false;
        }
        if (!capture(whole, quality, memb, bgr)) return false;
        // The template changed, the hand did not: the new lock is judged against the
        // likelihood tracking had (P_init kept), not re-measured on a template that may fit
        // its edges worse (a cut one), which would let it follow clutter with full confidence.
        awaiting_p_init = false;
        return true;
    }

    // Places the known template on a detected blob (palm to palm, finger direction to
    // finger direction), refines, and resumes tracking if it measures as well as tracking
    // did (lost_ratio x P_init).
    bool refit_known_shape(const Detection& found, const cv::Mat1b& memb, const cv::Mat& bgr) {
        HandLandmarks lm;
        try {
            lm = find_hand_landmarks(found.mask, found.motion);
        } catch (const std::invalid_argument&) {
            return false;
        }
        const double reach = std::hypot(shape->fingertip.x, shape->fingertip.y);
        const double found_reach = std::hypot(lm.fingertip.x - lm.palm.x, lm.fingertip.y - lm.palm.y);
        if (reach <= 0.0 || found_reach <= 0.0) return false;
        const HandState guess{
            lm.palm.x, lm.palm.y,
            std::atan2(lm.fingertip.y - lm.palm.y, lm.fingertip.x - lm.palm.x) -
                std::atan2(shape->fingertip.y, shape->fingertip.x),
            std::clamp(found_reach / reach, kMinScale, kMaxScale), previous.squash};
        const FitResult fit = refine_fit(memb, *shape, guess, FitParams{8, 8.0, 0.5, 2.0, 0.5});
        if (!fit.converged) return false;
        update_grey(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows));
        const double like =
            measurement.normal_likelihood(measurement.misfit(memb, grey, *shape, fit.state));
        if (like < params.lost_ratio * p_init) return false;
        skin = found.skin;
        start_tracking(fit.state);
        awaiting_p_init = false;
        report(fit.state);
        return true;
    }

    void start_tracking(const HandState& x0) {
        noise.reset();
        const NoiseVector& sd = noise.sigma();
        std::normal_distribution<double> z;
        const double w = 1.0 / particles.size();
        for (std::size_t i = 0; i < particles.size(); ++i) {
            HandState s = x0;
            if (i > 0) {  // keep X0 itself among the hypotheses
                s.x += sd[0] * z(rng);
                s.y += sd[1] * z(rng);
                s.rotation += sd[2] * z(rng);
                s.scale *= std::exp(sd[3] * z(rng));
            }
            particles[i] = Particle{s, w};
        }
        estimate.state = TrackState::Tracking;
        estimate.mean = estimate.best = x0;
        estimate.confidence = 1.0;
        previous = x0;
        awaiting_p_init = true;
        low_frames = 0;
        edges_were_weak = false;
        tracked_frames = 0;
        watch_everywhere = false;
        firm_area = std::abs(cv::contourArea(shape->outline)) * x0.scale * x0.scale * x0.squash;
        trial.reset();
        detector.reset();
    }

    // Re-initialisation guided by the skin map: the largest skin blobs of a plausible size
    // are tried as palm positions at the last rotation and scale; the best fit is taken if
    // it measures as well as tracking did (lost_ratio x P_init).
    bool reacquire_by_skin(const cv::Mat& bgr) {
        cv::Mat1b seg;
        skin->segment(bgr, seg);
        // Skin of the static scene (a face the hand was lost in front of) is left out, as
        // the detector does: the hand's blob is then the hand's alone.
        const cv::Mat1b& scene = static_scene(bgr, true, {});
        if (!scene.empty()) seg.setTo(0, scene);
        cv::morphologyEx(seg, seg, cv::MORPH_CLOSE,
                         cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
        cv::Mat1i labels;
        cv::Mat stats, centroids;
        const int count = cv::connectedComponentsWithStats(seg, labels, stats, centroids, 8, CV_32S);
        const double template_area = std::max(1.0, cv::contourArea(shape->outline));
        const double scale = estimate.mean.scale;
        skin->membership(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), membership);
        membership_roi = cv::Rect(0, 0, bgr.cols, bgr.rows);
        update_grey(bgr, membership_roi);
        double best_like = 0.0;
        HandState best_state;
        for (int i = 1; i < count; ++i) {
            const double area = stats.at<int>(i, cv::CC_STAT_AREA);
            const double ratio = area / (template_area * scale * scale * estimate.mean.squash);
            if (ratio < 0.4 || ratio > 3.0) continue;
            // The palm is the blob's thickest point.
            const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                               stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
            cv::Mat1b blob = labels(box) == i;
            cv::copyMakeBorder(blob, blob, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
            cv::Mat1f dist;
            cv::distanceTransform(blob, dist, cv::DIST_L2, cv::DIST_MASK_5);
            cv::Point at;
            cv::minMaxLoc(dist, nullptr, nullptr, nullptr, &at);
            const HandState guess{double(box.x + at.x - 1), double(box.y + at.y - 1),
                                  estimate.mean.rotation, scale, estimate.mean.squash};
            const FitResult fit = refine_fit(membership, *shape, guess, FitParams{8, 8.0, 0.5, 2.0, 0.5});
            if (!fit.converged) continue;
            const double like = measurement.normal_likelihood(
                measurement.misfit(membership, grey, *shape, fit.state));
            if (like > best_like) {
                best_like = like;
                best_state = fit.state;
            }
        }
        if (best_like < params.lost_ratio * p_init || best_like <= 0.0) return false;
        start_tracking(best_state);
        awaiting_p_init = false;  // the hand is known: keep the reference likelihood
        report(best_state);
        return true;
    }

    // --- one CONDENSATION iteration ----------------------------------------------------

    void track(const cv::Mat& bgr, const ImageMotion& motion) {
        const std::size_t n = particles.size();
        // Resample (systematic, O(N)), then predict through the zero-order dynamics plus the
        // camera-motion offset, with quasi-random noise.
        for (std::size_t i = 0; i < n; ++i) weights[i] = particles[i].weight;
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        systematic_resample(weights, unit(rng), ancestors);
        sampler.next_frame(deviates);
        const NoiseVector& sd = noise.sigma();
        double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300, max_s = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            HandState s = particles[ancestors[i]].state;
            const double* w = &deviates[4 * i];
            s.x += motion.dx + sd[0] * w[0];
            s.y += motion.dy + sd[1] * w[1];
            s.rotation += motion.drotation + sd[2] * w[2];
            s.scale = std::clamp(s.scale * motion.scale_factor * std::exp(sd[3] * w[3]), kMinScale,
                                 kMaxScale);
            s.squash = previous.squash;  // the shape, not a sampled dimension
            predicted[i].state = s;
            min_x = std::min(min_x, s.x);
            max_x = std::max(max_x, s.x);
            min_y = std::min(min_y, s.y);
            max_y = std::max(max_y, s.y);
            max_s = std::max(max_s, s.scale);
        }
        std::swap(particles, predicted);

        // The skin map once per frame, over the region the hypotheses can reach; the rest
        // of the map stays 0 (cleared where the previous region was).
        const double reach = max_s * std::max(1.0, previous.squash) * template_radius +
                             measurement.params().half_window + 2.0;
        const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
        const cv::Rect roi = cv::Rect(cv::Point(int(std::floor(min_x - reach)), int(std::floor(min_y - reach))),
                                      cv::Point(int(std::ceil(max_x + reach)) + 1, int(std::ceil(max_y + reach)) + 1)) &
                             frame;
        if (membership_roi.area() > 0) membership(membership_roi).setTo(0);
        skin->membership(bgr, roi, membership);
        membership_roi = roi;
        // While the edges are weak the hand is likely in front of skin (a face, a
        // skin-coloured object), and the normals from skin into skin are measured on the
        // grey levels. Elsewhere such normals are few and the skin edges decide alone,
        // which spares the grey map's cost on most frames. Not with a template that is not
        // even pointing-shaped: its outline is not the hand's silhouette, and inside a face
        // grey steps (eyes, brows, mouth) are everywhere for it to settle on.
        const bool use_steps = edges_were_weak && template_quality != CaptureQuality::Unsure;
        const cv::Mat1b& steps = use_steps ? grey : no_map;
        if (use_steps) update_steps(bgr, roi);

        // Weight by the observation density.
        std::size_t best = 0;
        double best_misfit = 2.0;
        const double margin = measurement.negligible_margin();
        for (std::size_t i = 0; i < n; ++i) {
            const double q =
                measurement.misfit(membership, steps, *shape, particles[i].state, best_misfit + margin);
            log_weights[i] = measurement.log_likelihood(q);
            if (q < best_misfit) {
                best_misfit = q;
                best = i;
            }
        }
        normalise_log_weights(log_weights);
        for (std::size_t i = 0; i < n; ++i) particles[i].weight = log_weights[i];

        // Estimates: the weighted mean (rotation about the best one, scale geometric) and
        // the best hypothesis.
        const HandState& b = particles[best].state;
        HandState mean{0.0, 0.0, 0.0, 0.0};
        double log_s = 0.0;
        for (const Particle& p : particles) {
            mean.x += p.weight * p.state.x;
            mean.y += p.weight * p.state.y;
            mean.rotation += p.weight * wrap_angle(p.state.rotation - b.rotation);
            log_s += p.weight * std::log(p.state.scale);
        }
        mean.rotation += b.rotation;
        mean.scale = std::exp(log_s);
        mean.squash = previous.squash;
        estimate.mean = mean;
        estimate.best = b;

        const double best_like = measurement.normal_likelihood(best_misfit);
        if (awaiting_p_init) {
            p_init = best_like;
            awaiting_p_init = false;
        }
        estimate.confidence = p_init > 0.0 ? std::clamp(best_like / p_init, 0.0, 1.0) : 0.0;
        const bool weak_edges = best_like < params.lost_ratio * p_init;
        // Whether the next frame measures grey steps is judged on the skin edges alone:
        // judged with the steps, finding them would switch them off on the next frame and
        // the density would alternate between two landscapes, frame by frame.
        edges_were_weak = use_steps ? measurement.normal_likelihood(measurement.misfit(
                                          membership, no_map, *shape, b)) < params.lost_ratio * p_init
                                    : weak_edges;

        // Refine from the better of mean and best; report that. The squash follows the
        // hand's turn only while its edges fit (where they are weak, in front of a face,
        // the outline's horizontal extent is not seen), and only for a clean template: one
        // merged with something else would use it to stretch over that.
        const double mean_misfit = measurement.misfit(membership, steps, *shape, mean);
        const HandState start = mean_misfit <= best_misfit ? mean : b;
        FitParams refine;
        refine.fit_squash = !weak_edges && template_quality == CaptureQuality::Clean;
        const FitResult fit = refine_fit(membership, *shape, start, refine, bgr);
        const HandState out = fit.converged ? fit.state : start;

        // Lost when the edges no longer fit (thesis: every likelihood < lost_ratio x P_init),
        // not even the refined contour's, and the contour's inner rim is no longer skin.
        // Edges also vanish where the hand passes in front of a face or a skin-coloured
        // object; there the hand is still under the contour, and tracking goes on while the
        // rim is skin, while the edges that can still be seen (not skin against skin) fit
        // as well as tracking did, or while the contour outlines something that moved in
        // front of the learnt scene. The refined contour is the best placed one to judge.
        if (weak_edges && !hand_still_there(out, steps, bgr)) {
            if (++low_frames >= params.lost_frames) {
                lose();
                return;
            }
        } else {
            low_frames = 0;
        }

        // While the edges are weak the hand may be touching a face or a skin-coloured
        // object, and a capture now could merge it: a candidate larger than the tracked
        // hand waits for a frame where the hand stands apart. A smaller one may still
        // drop what a merged template holds, but not by a verdict taken on such a frame,
        // where part of either outline may be unseen.
        // The area the edges last fitted can itself be wrong: a contour shrunk onto a piece
        // of the hand (a merged template's scale collapsing) still fits edges there. So a
        // candidate is stepped on at least one frame first, and one whose outline has agreed
        // with the image clearly better than the tracked one's on every frame so far
        // (TemplateTrial::clearly_better) is not dropped for its size.
        if (weak_edges && trial && trial->frames() > 0 && !trial->clearly_better() &&
            grows_hand(cv::contourArea(trial->candidate().outline) * trial->state().scale *
                       trial->state().scale))
            trial.reset();
        if (trial && try_template(bgr, out, fit.converged ? fit.agreement : 0.0, !weak_edges))
            return;
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

    // One frame of the trial; true if the candidate won (and `may_replace`) and tracking
    // restarted on it, judged against the same P_init (the hand did not change).
    bool try_template(const cv::Mat& bgr, const HandState& out, double current, bool may_replace) {
        auto verdict = trial->step(membership, bgr, previous, out, current);
        if (verdict == TemplateTrial::Verdict::Running) return false;
        // Edges cannot tell a template merged with a static skin-coloured object from the
        // hand alone while the hand stays by the object; the learnt scene can: the merged
        // one holds some of it, the hand does not.
        if (verdict == TemplateTrial::Verdict::Kept && holds_less_scene(out, bgr))
            verdict = TemplateTrial::Verdict::Replaced;
        if (verdict == TemplateTrial::Verdict::Kept || !may_replace) {
            trial.reset();
            return false;
        }
        TemplateTrial won = std::move(*trial);
        adopt(std::move(won.candidate()), won.skin(), template_quality, won.state());
        awaiting_p_init = false;
        return true;
    }

    // Whether the tracked contour at `out` holds the learnt static scene along its inner rim
    // (at least kMergedSceneFraction of it, more than a hand alone shows) and the trial's
    // candidate at most half as much.
    bool holds_less_scene(const HandState& out, const cv::Mat& bgr) const {
        const RimSurvey tracked = survey_rim(out, bgr);
        if (tracked.scene < kMergedSceneFraction * tracked.points) return false;
        const RimSurvey candidate = survey_rim(trial->candidate(), trial->state(), bgr);
        return double(candidate.scene) / candidate.points <= 0.5 * double(tracked.scene) / tracked.points;
    }

    // Whether at least kOnSceneFraction of the inner rim of the contour at `s` is the learnt
    // static scene (false while none is learnt).
    bool lies_on_scene(const HandState& s, const cv::Mat& bgr) const {
        const RimSurvey rim = survey_rim(s, bgr);
        return rim.scene >= kOnSceneFraction * rim.points;
    }

    // Whether the reported contour lies inside the watched `window` and less than
    // kStillMotion of it changed during the watch (`moved`: the window's recent motion).
    bool contour_held_still(const cv::Mat1b& moved, const cv::Rect& window) {
        const cv::Rect box = estimate.bbox & window;
        if (moved.size() != window.size() || box != estimate.bbox || box.area() == 0) return false;
        fill_contour(box);
        const cv::Mat1b under = moved(box - window.tl());
        int inside = 0, changed = 0;
        for (int y = 0; y < box.height; ++y) {
            const uchar* f = contour_fill.ptr<uchar>(y);
            const uchar* m = under.ptr<uchar>(y);
            for (int x = 0; x < box.width; ++x) {
                inside += f[x] != 0;
                changed += f[x] != 0 && m[x] != 0;
            }
        }
        return inside > 0 && changed < kStillMotion * inside;
    }

    // `box` grown about its centre to at least `side` x `side`.
    static cv::Rect at_least(const cv::Rect& box, int side) {
        const int w = std::max(box.width, side), h = std::max(box.height, side);
        return {box.x - (w - box.width) / 2, box.y - (h - box.height) / 2, w, h};
    }

    // True when a capture of `area` pixels is clearly larger than the hand was when its
    // edges last fitted (the contour reported since may have shrunk or slid off it).
    bool grows_hand(double area) const { return area > kMaxCaptureGrowth * firm_area; }

    // On a weak-edge frame: whether the contour at `s` still holds the hand (see track()).
    bool hand_still_there(const HandState& s, const cv::Mat1b& steps, const cv::Mat& bgr) const {
        const double like =
            measurement.normal_likelihood(measurement.misfit(membership, steps, *shape, s));
        if (like >= params.lost_ratio * p_init) return true;
        const RimSurvey rim = survey_rim(s, bgr);
        return rim_is_skin(rim) || visible_edges_fit(s) || outlines_foreground(rim);
    }

    // True when the normals that are not skin against skin carry enough of the weight and
    // fit them as well as tracking did (lost_ratio x P_init).
    bool visible_edges_fit(const HandState& s) const {
        double judged = 0.0;
        const double q = measurement.judged_misfit(membership, *shape, s, judged);
        return judged >= kMinJudgedWeight &&
               measurement.normal_likelihood(q) >= params.lost_ratio * p_init;
    }

    // What lies just inside (2.5 px in along the normals) and just outside the contour's
    // outline points: skin, and against the learnt static scene.
    struct RimSurvey {
        int points = 0;
        bool in_view = true;  // every inner point inside the frame
        int skin = 0, finger = 0, finger_skin = 0;
        int moved = 0, scene = 0;  // inner points known to differ from the scene / the scene
        int scene_outside = 0;     // outer points that match the scene (Scene or Unsure)
    };

    RimSurvey survey_rim(const HandState& s, const cv::Mat& bgr) const {
        return survey_rim(*shape, s, bgr);
    }

    // The same along the outline of template `t` (a trial's candidate) at `s`.
    RimSurvey survey_rim(const HandTemplate& t, const HandState& s, const cv::Mat& bgr) const {
        RimSurvey rim;
        rim.points = static_cast<int>(t.outline.size());
        const cv::Rect frame(0, 0, membership.cols, membership.rows);
        const bool scene_known = params.use_static_scene && !background.empty();
        for (std::size_t i = 0; i < t.outline.size(); ++i) {
            const cv::Point2d p = place(s, t.outline[i]);
            const cv::Point2d n = kRimDepth * place_normal(s, t.outline_normals[i]);
            const cv::Point in(cvRound(p.x - n.x), cvRound(p.y - n.y));
            const bool inside = in.inside(frame);
            rim.in_view = rim.in_view && inside;
            const bool skin = inside && membership(in) >= kSkinEdgeLevel;
            rim.skin += skin;
            if (t.on_finger(t.outline[i])) {
                ++rim.finger;
                rim.finger_skin += skin;
            }
            if (!scene_known) continue;
            if (inside) {
                const StaticBackground::Look look = background.look(bgr, in);
                rim.moved += look == StaticBackground::Look::Foreground;
                rim.scene += look == StaticBackground::Look::Scene;
            }
            const cv::Point out(cvRound(p.x + n.x), cvRound(p.y + n.y));
            if (out.inside(frame)) {
                const StaticBackground::Look look = background.look(bgr, out);
                rim.scene_outside += look == StaticBackground::Look::Scene || look == StaticBackground::Look::Unsure;
            }
        }
        return rim;
    }

    // Whether the skin of the inner rim says the hand is under the contour: nearly all of
    // the rim above the boundary level, or most of it with nearly all of the finger's. The
    // hand's own rim falls short mostly along the creases of the curled fingers; a contour
    // turned or slid off the hand keeps most of the palm's rim but not the finger's, and
    // the finger carries the direction. A contour cut by the image border is held to the
    // first rule: there the rim is missing for want of image, and a hand pushed to the
    // border by the head's turn is better found again whole.
    static bool rim_is_skin(const RimSurvey& rim) {
        const double all = double(rim.skin) / rim.points;
        const double finger = rim.finger > 0 ? double(rim.finger_skin) / rim.finger : 0.0;
        return all >= kRimSkinFraction ||
               (rim.in_view && all >= kLooseRimSkinFraction && finger >= kRimSkinFraction);
    }

    // Whether the contour outlines something that moved in front of the learnt static
    // scene, with skin on at least half its rim (a hand, not a sleeve): just inside it, at
    // least half known to differ from the scene and hardly any of it the scene; just
    // outside it, at least half matching the scene (a point next to something that does
    // not, Unsure, counts: the outer rim runs 1.5 px from the hand's edge, and along the
    // wrist it borders the moving arm). In front of a face, skin cannot tell the hand
    // from the face behind it, and a hand turned away from the rigid template shows less
    // of the template's rim; the scene can. A contour slid onto the face has the face, the
    // scene, inside it; one shrunk or slid within the hand and arm has them outside it.
    // Without a learnt scene the counts are 0 and this is false.
    static bool outlines_foreground(const RimSurvey& rim) {
        const double points = rim.points;
        return rim.skin >= kForegroundRimSkinFraction * points && rim.moved >= kMovedFraction * points &&
               rim.scene <= kMaxSceneInsideFraction * points &&
               rim.scene_outside >= kSceneOutsideFraction * points;
    }

    void lose() {
        estimate.state = TrackState::Lost;
        estimate.confidence = 0.0;
        estimate.contour.clear();
        estimate.bbox = {};
        low_frames = 0;
        lost_search = 0;
        detector.reset();
    }

    // Where the frame shows the static scene, over `roi` (empty: the whole frame), for a
    // segmentation of this frame (`wanted`: the detector's, or the skin search after a
    // loss); else, or while it is unknown, empty.
    const cv::Mat1b& static_scene(const cv::Mat& bgr, bool wanted, cv::Rect roi) {
        if (!wanted || !params.use_static_scene) return no_map;
        if (roi.area() == 0) roi = cv::Rect(0, 0, bgr.cols, bgr.rows);
        return background.find_static(bgr, roi);
    }

    // The static scene is learnt everywhere but on and around the tracked hand (its
    // contour grown by the search window), so that a hand held still is not learnt into it,
    // while the scene between the fingers and around the hand is.
    void learn_background(const cv::Mat& bgr) {
        if (!estimate.valid()) {
            background.learn(bgr);
            return;
        }
        const int grow = measurement.params().half_window;
        const cv::Rect box = cv::Rect(estimate.bbox.x - grow, estimate.bbox.y - grow,
                                      estimate.bbox.width + 2 * grow, estimate.bbox.height + 2 * grow) &
                             cv::Rect(0, 0, bgr.cols, bgr.rows);
        if (box.area() == 0) {
            background.learn(bgr);
            return;
        }
        fill_contour(box);
        // The outline drawn 2 x grow + 1 px thick with round ends: the filled contour
        // grown by `grow` (a dilation by a disc, at a fraction of its cost).
        const cv::Point* poly = fill_points.data();
        const int count = static_cast<int>(fill_points.size());
        cv::polylines(contour_fill, &poly, &count, 1, true, 255, 2 * grow + 1);
        background.learn(bgr, box, contour_fill);
    }

    // The grey map over `roi`, for the normals that run from skin into skin: levels above
    // kSceneGreyLevel, which is kept for the learnt scene (update_steps).
    void update_grey(const cv::Mat& bgr, const cv::Rect& roi) {
        if (grey.size() != bgr.size()) grey = cv::Mat1b(bgr.size(), kSceneGreyLevel);
        cv::Mat part = grey(roi);
        cv::cvtColor(bgr(roi), part, cv::COLOR_BGR2GRAY);
        cv::max(part, kSceneGreyLevel + 1, part);
    }

    // The grey map over `roi` with the learnt static scene blanked: in front of a face
    // the step that counts is where the moving hand meets the scene behind it, and the
    // face's own steps (eyes, brows, mouth), with the scene on both sides, are gone.
    // Where no scene is learnt, the plain grey levels.
    void update_steps(const cv::Mat& bgr, const cv::Rect& roi) {
        update_grey(bgr, roi);
        const cv::Mat1b& scene = static_scene(bgr, true, roi);
        if (!scene.empty()) grey(roi).setTo(kSceneGreyLevel, scene(roi));
    }

    // --- reporting ---------------------------------------------------------------------

    void report(const HandState& s) {
        estimate.contour.resize(shape->outline.size());
        for (std::size_t i = 0; i < shape->outline.size(); ++i)
            estimate.contour[i] = cv::Point2f(place(s, shape->outline[i]));
        estimate.bbox = cv::boundingRect(estimate.contour);
        estimate.palm = cv::Point2f(float(s.x), float(s.y));
        estimate.fingertip = cv::Point2f(place(s, shape->fingertip));
        // Image y points down; the reported angle is counter-clockwise with y up.
        estimate.pointing_deg = std::atan2(-(estimate.fingertip.y - estimate.palm.y),
                                           estimate.fingertip.x - estimate.palm.x) *
                                180.0 / std::numbers::pi;
    }

    // The skin mean follows the lighting, sampled inside the tracked contour (shrunk by
    // a few pixels so the boundary's mixed pixels stay out). Only the contour's box is
    // touched.
    void adapt_skin(const cv::Mat& bgr) {
        const cv::Rect box = estimate.bbox & cv::Rect(0, 0, bgr.cols, bgr.rows);
        if (box.width < 8 || box.height < 8) return;
        fill_contour(box);
        cv::erode(contour_fill, contour_fill, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
        skin->update_mean(bgr(box), contour_fill, kAdaptRate);
    }

    // contour_fill: the reported contour filled, over `box` (in image pixels).
    void fill_contour(const cv::Rect& box) {
        contour_fill.create(box.size());
        contour_fill.setTo(0);
        fill_points.resize(estimate.contour.size());
        for (std::size_t i = 0; i < fill_points.size(); ++i)
            fill_points[i] = cv::Point(cvRound(estimate.contour[i].x) - box.x,
                                       cvRound(estimate.contour[i].y) - box.y);
        const cv::Point* poly = fill_points.data();
        const int count = static_cast<int>(fill_points.size());
        cv::fillPoly(contour_fill, &poly, &count, 1, 255);
    }
};

HandTracker::HandTracker(const TrackerParams& params) : impl_(std::make_unique<Impl>(params)) {}
HandTracker::~HandTracker() = default;
HandTracker::HandTracker(HandTracker&&) noexcept = default;
HandTracker& HandTracker::operator=(HandTracker&&) noexcept = default;

const EyeEstimate& HandTracker::process(const cv::Mat& bgr, const ImageMotion& camera_motion) {
    return impl_->process(bgr, camera_motion);
}

void HandTracker::reset() { impl_->reset(); }
const EyeEstimate& HandTracker::estimate() const { return impl_->estimate; }
std::span<const Particle> HandTracker::particles() const { return impl_->particles; }
const TrackerParams& HandTracker::params() const { return impl_->params; }

}  // namespace gc
