// Which template the filter tracks: the first capture from a detection, the watches that
// look for a better capture while the template is not clean, and the trials that decide
// between the tracked template and a candidate of the same quality.
#include "tracker/hand_tracker_impl.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

namespace {

constexpr double kMaxCaptureGrowth = 1.15;  // area ratio: a capture this much larger adds something
constexpr int kLostSearchEvery = 3;
constexpr int kRecapturePeriod = 16;       // while the template is provisional, look again this often
constexpr int kUnsureRecapturePeriod = 8;  // ... and this often while it is not even pointing-shaped
constexpr int kRecaptureFrames = 7;        // ... over this many frames (history_frames + 1)
constexpr double kStillMotion = 0.02;      // moved share of the contour below which it held still

// A template's state in the frame it was captured from.
HandState as_captured(const HandTemplate& t) { return HandState{t.origin_px.x, t.origin_px.y, 0.0, 1.0}; }

std::optional<HandTemplate> template_from(const Detection& found, const cv::Mat1b& memb, const cv::Mat& bgr)
{
    try {
        return HandTemplate::from_mask(found.mask, memb, TemplateOptions{}, bgr, found.motion);
    } catch (const std::invalid_argument&) {
        return std::nullopt;  // a moving blob without a finger: keep waiting
    }
}

// `box` grown about its centre to at least `side` x `side`.
cv::Rect at_least(const cv::Rect& box, int side)
{
    const int w = std::max(box.width, side), h = std::max(box.height, side);
    return {box.x - (w - box.width) / 2, box.y - (h - box.height) / 2, w, h};
}

bool touches_border(const cv::Rect& box, const cv::Size& area)
{
    return box.x <= 1 || box.y <= 1 || box.br().x >= area.width - 1 || box.br().y >= area.height - 1;
}

}  // namespace

void HandTracker::Impl::acquire(const cv::Mat& bgr)
{
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
    if (touches_border(cv::boundingRect(found->mask), bgr.size())) return;
    cv::Mat1b memb(bgr.size(), uchar(0));
    found->skin.membership(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), memb);
    // The hand seen before is kept when it fits the detection: a new capture could include
    // skin-coloured things the hand touches at this moment. Unless the known template was
    // itself unsure and this capture is clean.
    const CaptureQuality quality = capture_quality(*found);
    const bool cleaner = template_quality != CaptureQuality::Clean && quality == CaptureQuality::Clean;
    if (shape && skin && !cleaner && refit_known_shape(*found, memb, bgr)) return;
    capture(*found, quality, memb, bgr);
}

// A new template from a detection; false (nothing changed) if the blob has no finger.
bool HandTracker::Impl::capture(const Detection& found, CaptureQuality quality, const cv::Mat1b& memb,
                                const cv::Mat& bgr)
{
    auto captured = template_from(found, memb, bgr);
    if (!captured) return false;
    const HandState at = as_captured(*captured);
    adopt(std::move(*captured), found.skin, quality, at);
    return true;
}

void HandTracker::Impl::adopt(HandTemplate&& t, const SkinModel& model, CaptureQuality quality, const HandState& at,
                              TrackStart start)
{
    shape = std::move(t);
    skin = model;
    template_radius = 0.0;
    for (const auto& p : shape->outline) template_radius = std::max(template_radius, double(std::hypot(p.x, p.y)));
    const cv::Rect extent = cv::boundingRect(shape->outline);
    template_side = std::max(extent.width, extent.height);
    start_tracking(at, start);
    template_quality = quality;
    report(at);
}

// While the template is not clean, the detector looks again now and then: every
// kRecapturePeriod frames it watches kRecaptureFrames consecutive frames of a window around
// the tracked hand (three times its box, the box at least as large as the template's larger
// side, so that a contour shrunk onto a sliver of the hand still watches a window the hand
// fits in) and segments the last one. A capture of better quality (clean over
// pointing-shaped over neither) of a hand wholly inside the window, overlapping the tracked
// one, replaces the template; while the edges are weak, only one no larger than the hand.
// The hand is what waved: a watch that saw (nearly) nothing change under the tracked
// contour says it may hold a static skin-coloured object instead. The next watch then
// covers the whole frame, and there a capture need not overlap the tracked contour.
bool HandTracker::Impl::recapture(const cv::Mat& bgr, bool weak_edges)
{
    const int period =
        template_quality == CaptureQuality::Unsure || watch_everywhere ? kUnsureRecapturePeriod : kRecapturePeriod;
    const int phase = tracked_frames % period;
    const int first = period - kRecaptureFrames;
    if (phase < first) return false;
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    if (phase == first) {
        const cv::Rect b = at_least(estimate.bbox, template_side);
        recapture_roi =
            watch_everywhere ? frame : cv::Rect(b.x - b.width, b.y - b.height, 3 * b.width, 3 * b.height) & frame;
        detector.reset();
    }
    if (recapture_roi.width < 32 || recapture_roi.height < 32) return false;
    const bool last = phase == period - 1;
    const cv::Mat1b& scene = static_scene(bgr, last, recapture_roi);
    const auto found = detector.process(bgr(recapture_roi), *skin, last, scene.empty() ? scene : scene(recapture_roi));
    const bool everywhere = recapture_roi == frame && watch_everywhere;
    if (last) {
        watch_everywhere = contour_held_still(detector.recent_motion(), recapture_roi);
        detector.reset();
    }
    // Two watches in a row saw the contour hold still while this hand moved elsewhere: the
    // contour is on something static, and a capture of its rank away from it replaces it
    // without a trial (which would move it with the static contour).
    const bool still_twice = everywhere && watch_everywhere;
    if (!found) return false;
    const CaptureQuality quality = capture_quality(*found);
    if (quality < template_quality) return false;
    if (weak_edges && grows_hand(found->area)) return false;
    return replace_from_watch(bgr, *found, quality, everywhere, still_twice);
}

// The watch's capture `found` (in window pixels) replaces the template, or goes on trial
// against it when both are of the same quality.
bool HandTracker::Impl::replace_from_watch(const cv::Mat& bgr, const Detection& found, CaptureQuality quality,
                                           bool everywhere, bool still_twice)
{
    const cv::Rect local = cv::boundingRect(found.mask);
    const bool apart = ((local + recapture_roi.tl()) & estimate.bbox).area() == 0;
    // A contour whose inner rim is mostly the learnt scene has been left on a static thing
    // (a template merged with it, the hand gone on): a capture of its rank replaces it
    // without a trial, wherever it is in the window.
    const bool on_scene = lies_on_scene(previous, bgr);
    const bool equal = quality == template_quality && !(still_twice && apart) && !on_scene;
    if (equal && trial) return false;
    if (touches_border(local, recapture_roi.size())) return false;  // cut by the window: not the whole hand
    if (!everywhere && apart && !on_scene) return false;
    Detection whole = found;
    whole.mask = cv::Mat1b(bgr.size(), uchar(0));
    found.mask.copyTo(whole.mask(recapture_roi));
    whole.motion = cv::Mat1b(bgr.size(), uchar(0));
    if (!found.motion.empty()) found.motion.copyTo(whole.motion(recapture_roi));
    cv::Mat1b memb(bgr.size(), uchar(0));
    found.skin.membership(bgr, recapture_roi, memb);
    if (equal) {
        auto candidate = template_from(whole, memb, bgr);
        if (!candidate) return false;
        const HandState at = as_captured(*candidate);
        trial.emplace(std::move(*candidate), whole.skin, at);
        return false;
    }
    if (!capture(whole, quality, memb, bgr)) return false;
    // The template changed, the hand did not: the new lock is judged against the likelihood
    // tracking had (P_init kept), not re-measured on a template that may fit its edges
    // worse (a cut one), which would let it follow clutter with full confidence.
    awaiting_p_init = false;
    return true;
}

// One frame of the trial; true if the candidate won (and `may_replace`) and tracking
// restarted on it, judged against the same P_init (the hand did not change).
bool HandTracker::Impl::try_template(const cv::Mat& bgr, const HandState& out, double current, bool may_replace)
{
    auto verdict = trial->step(membership, bgr, previous, out, current);
    if (verdict == TemplateTrial::Verdict::Running) return false;
    // Edges cannot tell a template merged with a static skin-coloured object from the hand
    // alone while the hand stays by the object; the learnt scene can: the merged one holds
    // some of it, the hand does not.
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
// (more than a hand alone shows) and the trial's candidate at most half as much.
bool HandTracker::Impl::holds_less_scene(const HandState& out, const cv::Mat& bgr) const
{
    const RimSurvey tracked = survey_rim(*shape, out, membership, known_scene(), bgr);
    if (tracked.scene < kMergedSceneFraction * tracked.points) return false;
    const RimSurvey candidate = survey_rim(trial->candidate(), trial->state(), membership, known_scene(), bgr);
    return double(candidate.scene) / candidate.points <= 0.5 * double(tracked.scene) / tracked.points;
}

// Whether most of the inner rim of the contour at `s` is the learnt static scene.
bool HandTracker::Impl::lies_on_scene(const HandState& s, const cv::Mat& bgr) const
{
    const RimSurvey rim = survey_rim(*shape, s, membership, known_scene(), bgr);
    return rim.scene >= kOnSceneFraction * rim.points;
}

// Whether the reported contour lies inside the watched `window` and less than kStillMotion
// of it changed during the watch (`moved`: the window's recent motion).
bool HandTracker::Impl::contour_held_still(const cv::Mat1b& moved, const cv::Rect& window)
{
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

// True when a capture of `area` pixels is clearly larger than the hand was when its edges
// last fitted (the contour reported since may have shrunk or slid off it).
bool HandTracker::Impl::grows_hand(double area) const { return area > kMaxCaptureGrowth * firm_area; }

}  // namespace gc
