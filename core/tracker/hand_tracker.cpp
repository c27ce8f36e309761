// The per-frame loop of one eye's tracker, as in the thesis: acquire the hand until a
// template is captured, then one CONDENSATION iteration per frame (condensation_step.cpp),
// with the static scene learnt behind the hand on every frame.
#include "tracker/hand_tracker_impl.hpp"

#include "measure/contour_measurement.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

constexpr int kMinFrameSide = 32;

void check_frame(const cv::Mat& bgr)
{
    if (bgr.empty()) throw std::invalid_argument("HandTracker: empty frame");
    if (bgr.type() != CV_8UC3)
        throw std::invalid_argument("HandTracker: expected a CV_8UC3 (BGR) frame, got " +
                                    std::to_string(bgr.channels()) + " channel(s) of depth " +
                                    std::to_string(bgr.depth()));
    if (bgr.cols < kMinFrameSide || bgr.rows < kMinFrameSide)
        throw std::invalid_argument("HandTracker: frame " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                                    " is smaller than 32x32");
}

const TrackerParams& checked(const TrackerParams& p)
{
    if (p.particles < 1) throw std::invalid_argument("HandTracker: particles must be >= 1");
    if (p.particles > 1'000'000) throw std::invalid_argument("HandTracker: particles must be <= 1000000");
    if (!(p.lost_ratio > 0.0 && p.lost_ratio < 1.0))
        throw std::invalid_argument("HandTracker: lost_ratio must be in (0, 1)");
    if (p.lost_frames < 1) throw std::invalid_argument("HandTracker: lost_frames must be >= 1");
    return p;
}

void check_motion(const ImageMotion& m)
{
    if (!std::isfinite(m.dx) || !std::isfinite(m.dy) || !std::isfinite(m.drotation) || !(m.scale_factor > 0.0) ||
        !std::isfinite(m.scale_factor))
        throw std::invalid_argument("HandTracker: camera motion must be finite with scale_factor > 0");
}

}  // namespace

HandTracker::Impl::Impl(const TrackerParams& p)
    : TrackerSession(checked(p)), params(p), predicted(p.particles), log_weights(p.particles), weights(p.particles),
      deviates(4 * static_cast<std::size_t>(p.particles)), ancestors(p.particles)
{
    if (p.detector == HandDetector::Learned) finder = std::make_unique<HandFinder>(HandFinderParams{p.model_dir});
}

void HandTracker::Impl::reset() { static_cast<TrackerSession&>(*this) = TrackerSession(params); }

const EyeEstimate& HandTracker::Impl::process(const cv::Mat& bgr, const ImageMotion& motion)
{
    check_frame(bgr);
    check_motion(motion);
    if (frame_size.area() > 0 && bgr.size() != frame_size)
        throw std::invalid_argument("HandTracker: frame size changed from " + std::to_string(frame_size.width) + "x" +
                                    std::to_string(frame_size.height) + " to " + std::to_string(bgr.cols) + "x" +
                                    std::to_string(bgr.rows) + " without reset()");
    frame_size = bgr.size();
    if (membership.size() != frame_size) {
        membership = cv::Mat1b(frame_size, uchar(0));
        membership_roi = {};
    }
    // The view moved without a word from the head (moved by someone else, a bumped tripod):
    // the hypotheses follow the scene's shift, and the landmark model checks the contour on
    // this very frame. Without the learned models nothing could check, and nothing looks.
    const bool told = motion.moves();
    const ViewChange seen = finder ? view.update(bgr) : ViewChange{};
    const bool unannounced = !told && (seen.shifted || seen.cut);
    ImageMotion moved = motion;
    if (!told && seen.shifted) {
        moved.dx = seen.dx;
        moved.dy = seen.dy;
    }
    // A turn of the head moves the scene in the image: its median starts again.
    if (told || unannounced) background.reset();
    if (unannounced) detector.reset();
    estimate.models_ran = false;
    const bool was_tracking = estimate.state == TrackState::Tracking;
    if (was_tracking) track(bgr, moved);
    const bool carried = finder && was_tracking && estimate.state == TrackState::Tracking && flow.ready();
    const bool finger_bent = carried && carry_key_points(bgr);
    if (!finder) {
        if (!was_tracking) acquire(bgr);
    } else if (estimate.state == TrackState::Tracking) {
        check_with_models(bgr, unannounced || finger_bent);
        watch_for_moving_hand(bgr, told || seen.shifted);
    } else {
        search_with_models(bgr);  // a hand lost on this frame is looked for at once
    }
    if (finder) keep_key_points(bgr, carried);
    if (params.use_static_scene) learn_background(bgr);
    return estimate;
}

// Spreads the particles around x0 (x0 itself kept among them) and starts tracking there.
void HandTracker::Impl::start_tracking(const HandState& x0, TrackStart start)
{
    if (start == TrackStart::NewHand) noise.reset();
    const NoiseVector& sd = noise.sigma();
    std::normal_distribution<double> z;
    const double w = 1.0 / particles.size();
    for (std::size_t i = 0; i < particles.size(); ++i) {
        HandState s = x0;
        if (i > 0) {
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

void HandTracker::Impl::lose()
{
    estimate.state = TrackState::Lost;
    estimate.confidence = 0.0;
    estimate.contour.clear();
    estimate.bbox = {};
    estimate.landmarks.clear();
    estimate.gesture = gesture = Gesture::Unknown;
    has_key_points = false;
    search_turn = 0;
    low_frames = 0;
    lost_search = 0;
    detector.reset();
}

void HandTracker::Impl::report(const HandState& s)
{
    estimate.contour.resize(shape->outline.size());
    for (std::size_t i = 0; i < shape->outline.size(); ++i)
        estimate.contour[i] = cv::Point2f(place(s, shape->outline[i]));
    estimate.bbox = cv::boundingRect(estimate.contour);
    estimate.palm = cv::Point2f(float(s.x), float(s.y));
    estimate.fingertip = cv::Point2f(place(s, shape->fingertip));
    estimate.gesture = gesture;
    if (has_key_points) place_key_points(s);
    // Image y points down; the reported angle is counter-clockwise with y up.
    estimate.pointing_deg =
        std::atan2(-(estimate.fingertip.y - estimate.palm.y), estimate.fingertip.x - estimate.palm.x) * 180.0 /
        std::numbers::pi;
}

HandTracker::HandTracker(const TrackerParams& params) : impl_(std::make_unique<Impl>(params)) {}
HandTracker::~HandTracker() = default;
HandTracker::HandTracker(HandTracker&&) noexcept = default;
HandTracker& HandTracker::operator=(HandTracker&&) noexcept = default;

const EyeEstimate& HandTracker::process(const cv::Mat& bgr, const ImageMotion& camera_motion)
{
    return impl_->process(bgr, camera_motion);
}

void HandTracker::reset() { impl_->reset(); }
const EyeEstimate& HandTracker::estimate() const { return impl_->estimate; }
std::span<const Particle> HandTracker::particles() const { return impl_->particles; }
const TrackerParams& HandTracker::params() const { return impl_->params; }

}  // namespace gc
