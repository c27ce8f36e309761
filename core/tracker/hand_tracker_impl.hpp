// HandTracker's insides, shared by the files that implement it: hand_tracker.cpp (the
// per-frame loop), condensation_step.cpp (one filter iteration), template_custody.cpp (which
// template is tracked: captures, re-captures, trials), reacquisition.cpp (finding a lost hand
// again), learned_custody.cpp (the learned models' search and checks), moving_hand_watch.cpp
// (a moving hand preferred to a still or unsettled one) and tracker_maps.cpp (the
// skin, grey and scene maps the others read).
#pragma once

#include "tracker/hand_tracker.hpp"

#include "background/static_background.hpp"
#include "contour/hand_template.hpp"
#include "detect/hand_finder.hpp"
#include "detect/motion_detector.hpp"
#include "detect/view_shift.hpp"
#include "filter/adaptive_noise.hpp"
#include "filter/quasi_random.hpp"
#include "measure/contour_measurement.hpp"
#include "skin/skin_model.hpp"
#include "tracker/key_point_flow.hpp"
#include "tracker/rim_survey.hpp"
#include "tracker/template_trial.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <vector>

namespace gc {

namespace tracking {

// Scale is relative to the template: a hand does not halve or double its distance while
// tracked, and tiny hypotheses would otherwise fit any small skin blob.
inline constexpr double kMinScale = 0.5;
inline constexpr double kMaxScale = 2.0;

}  // namespace tracking

// Everything that describes the hand being followed and the scene around it. A reset is
// one assignment of a fresh session, random streams included, so a reset tracker gives the
// same output as a new one with the same parameters.
struct TrackerSession {
    explicit TrackerSession(const TrackerParams& p)
        : sampler(4, p.seed ^ 0x5EEDULL), rng(p.seed), particles(p.particles)
    {
    }

    QuasiNormalSampler sampler;
    std::mt19937_64 rng;
    MotionDetector detector;
    ViewShift view;  // the view's own motion, for a camera that moved unannounced
    StaticBackground background;
    AdaptiveNoise noise;

    std::optional<SkinModel> skin;
    std::optional<HandTemplate> shape;
    double template_radius = 0.0;  // largest |u| of the outline, at scale 1
    int template_side = 0;         // larger side of the outline's box, at scale 1

    std::vector<Particle> particles;
    cv::Mat1b membership;
    cv::Rect membership_roi;
    cv::Mat1b grey;                // the frame's grey levels, where the membership map was computed
    bool edges_were_weak = false;  // on the last tracked frame (best_like < lost_ratio P_init)

    EyeEstimate estimate;
    cv::Size frame_size;
    double p_init = 0.0;  // per-normal likelihood of the first tracked iteration
    bool awaiting_p_init = false;
    int low_frames = 0;
    HandState previous;                                        // the last reported (refined) state
    CaptureQuality template_quality = CaptureQuality::Unsure;  // of the template's capture
    int tracked_frames = 0;                                    // since the last start_tracking
    double firm_area = 0.0;                                    // of the contour, on the last frame whose edges fitted
    int lost_search = 0;                                       // frames searched since the hand was lost
    cv::Rect recapture_roi;                                    // the window the detector watches while tracking
    bool watch_everywhere = false;                             // the last watch saw the tracked contour hold still

    std::optional<TemplateTrial> trial;  // a re-capture of the template's quality, on trial

    // The learned detector's key points, relative to the template (as its outline is), so
    // that the contour's state carries them between the landmark model's checks.
    bool has_key_points = false;
    std::array<cv::Point2f, 21> key_points{};
    Gesture gesture = Gesture::Unknown;
    std::optional<Gesture> new_gesture;  // read by the last check, not yet by two in a row
    bool template_cut = false;           // the template was made of a hand the frame's border cut
    int frames_since_check = 0;          // tracked frames since the landmark model last looked
    int check_interval = 1;              // frames between its checks: longer while the contour agrees
    int search_turn = 0;                 // frames searched by the palm detector without a hand
    KeyPointFlow flow;                   // carries the key points between the model's checks
    cv::Point2f still_anchor;            // where the contour was when it or the view last moved
    int still_frames = 0;                // tracked frames the contour has stayed with the room
    int unsettled_frames = 0;            // consecutive tracked frames the landmark model disagreed
    int view_still_frames = 0;           // consecutive tracked frames the view did not move
    bool watch_fed = false;              // the watch's motion detector saw the last tracked frame
};

struct HandTracker::Impl : TrackerSession {
    explicit Impl(const TrackerParams& p);

    TrackerParams params;
    ContourMeasurement measurement;
    std::unique_ptr<HandFinder> finder;  // the learned models; null in the motion-only mode
    const cv::Mat1b no_map;              // an empty map: no grey steps, no static scene

    // Scratch buffers of the filter step and the contour fill, sized once.
    std::vector<Particle> predicted;
    std::vector<double> log_weights, weights, deviates;
    std::vector<std::uint32_t> ancestors;
    cv::Mat1b contour_fill;
    std::vector<cv::Point> fill_points;

    // hand_tracker.cpp: the per-frame loop and the estimate it reports.
    void reset();
    const EyeEstimate& process(const cv::Mat& bgr, const ImageMotion& motion);
    // SameHand: a template made again on the tracked hand, which keeps the motion noise the
    // hand has taught and its gesture reading; NewHand: a hand just found.
    enum class TrackStart { NewHand, SameHand };
    void start_tracking(const HandState& x0, TrackStart start = TrackStart::NewHand);
    void lose();
    void report(const HandState& s);

    // condensation_step.cpp: one iteration of the filter, then the judgement of its result.
    void track(const cv::Mat& bgr, const ImageMotion& motion);
    struct Spread {
        double min_x, min_y, max_x, max_y, max_scale;
    };
    Spread predict(const ImageMotion& motion);
    bool map_skin(const cv::Mat& bgr, const Spread& spread);
    struct Weighed {
        HandState best, mean;
        double best_misfit;
        bool weak_edges;
    };
    Weighed weigh_and_judge(const cv::Mat1b& steps, bool use_steps);
    bool settle_trial(const cv::Mat& bgr, const HandState& out, double agreement, bool weak_edges);
    std::size_t weigh(const cv::Mat1b& steps, double& best_misfit);
    HandState weighted_mean(const HandState& best) const;
    bool hand_still_there(const HandState& s, const cv::Mat1b& steps, const cv::Mat& bgr) const;
    bool visible_edges_fit(const HandState& s) const;
    void follow(const cv::Mat& bgr, const HandState& out, const ImageMotion& motion, bool weak_edges);

    // template_custody.cpp: which template is tracked.
    void acquire(const cv::Mat& bgr);
    bool capture(const Detection& found, CaptureQuality quality, const cv::Mat1b& memb, const cv::Mat& bgr);
    void adopt(HandTemplate&& t, const SkinModel& model, CaptureQuality quality, const HandState& at,
               TrackStart start = TrackStart::NewHand);
    bool recapture(const cv::Mat& bgr, bool weak_edges);
    bool replace_from_watch(const cv::Mat& bgr, const Detection& found, CaptureQuality quality, bool everywhere,
                            bool still_twice);
    bool try_template(const cv::Mat& bgr, const HandState& out, double current, bool may_replace);
    bool holds_less_scene(const HandState& out, const cv::Mat& bgr) const;
    bool lies_on_scene(const HandState& s, const cv::Mat& bgr) const;
    bool contour_held_still(const cv::Mat1b& moved, const cv::Rect& window);
    bool grows_hand(double area) const;

    // reacquisition.cpp: a known hand found again after a loss.
    bool refit_known_shape(const Detection& found, const cv::Mat1b& memb, const cv::Mat& bgr);
    bool reacquire_by_skin(const cv::Mat& bgr);

    // learned_custody.cpp: the learned models find the hand, check the contour, give key points.
    void search_with_models(const cv::Mat& bgr);
    std::optional<FoundHand> search_where_it_moved(const cv::Mat& bgr, const Detection& moved);
    std::optional<FoundHand> confirm_detection(const cv::Mat& bgr, const Detection& found);
    void check_with_models(const cv::Mat& bgr, bool in_doubt);
    void take_gesture(Gesture read);
    bool adopt_found(const cv::Mat& bgr, const FoundHand& hand, TrackStart start = TrackStart::NewHand);
    void place_key_points(const HandState& s);
    bool carry_key_points(const cv::Mat& bgr);  // true: the flow bent the index finger
    void keep_key_points(const cv::Mat& bgr, bool carried);

    // moving_hand_watch.cpp: a moving hand takes over from one that holds still in the room.
    void watch_for_moving_hand(const cv::Mat& bgr, bool view_moved);
    static bool moves_inside(const Detection& found, const cv::Rect& box);

    // tracker_maps.cpp: the maps the steps above read.
    const StaticBackground* known_scene() const;
    const cv::Mat1b& static_scene(const cv::Mat& bgr, bool wanted, cv::Rect roi);
    void learn_background(const cv::Mat& bgr);
    void update_grey(const cv::Mat& bgr, const cv::Rect& roi);
    void update_steps(const cv::Mat& bgr, const cv::Rect& roi);
    void adapt_skin(const cv::Mat& bgr);
    void fill_contour(const cv::Rect& box);
};

}  // namespace gc
