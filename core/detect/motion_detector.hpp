// Acquisition of the hand (thesis 3.1): the user waves, the cameras hold still, and the
// hand is the only moving object. Two consecutive frames are differenced; inside the box of
// the change, the skin colour of the moving pixels is learnt (no fixed skin prior is
// trusted beyond a broad gate), the frame is segmented with it and closed, and the
// connected component that holds the motion is the hand.
#pragma once

#include "skin/skin_model.hpp"

#include <opencv2/core.hpp>

#include <optional>

namespace gc {

struct DetectionParams {
    // Grey levels: ~4 sigma of the difference of a typical sensor's noise. The least
    // threshold: raised per frame to 3 sigma of the noise the difference shows
    // (frame_noise_threshold), so that a noisy sensor does not flag a few percent of the
    // frame, more than the waving hand's own change.
    int diff_threshold = 12;
    int min_changed_pixels = 40;     // less change than this is not a waving hand
    int box_margin = 24;             // pixels added around the change box
    int close_size = 5;              // morphological close kernel (pixels, odd)
    int min_hand_area = 400;         // pixels
    double max_hand_fraction = 0.3;  // of the frame: a larger blob is not a hand
    double prior_gate_sigma = 3.0;   // candidate colours must lie this close to the prior
    int history_frames = 6;          // motion remembered for separating the hand from
    int history_reach = 15;          // ... static skin-coloured things it touches (pixels)
};

struct Detection {
    cv::Mat1b mask;     // frame-sized, 255 on the hand
    cv::Rect box;       // where the motion was
    SkinModel skin;     // fitted to the hand's pixels
    double area = 0.0;  // hand pixels
    // Fraction of the skin component within history_reach of recent motion (1 without a
    // history), before any cut: how sure the capture is to be the moving hand alone.
    double motion_support = 1.0;
    // The component was cut to the neighbourhood of recent motion, or skin of the static
    // scene was cleared off it: part of its outline may be the cut rather than the hand's.
    bool cut = false;
    cv::Mat1b motion = {};  // frame-sized, non-zero where the image changed recently (or empty)
};

// How sure a detection is to be the hand alone, worst first. Clean: nothing was cut off
// and nearly all of the skin component (kCleanSupport) lay near recent motion, so it is
// the moving hand alone; Pointing: shaped like a pointing hand but cut, or partly far from
// the motion (it may keep a remnant of a static skin-coloured thing the hand touched);
// Unsure: not even shaped like a pointing hand (hand_proportions).
enum class CaptureQuality { Unsure, Pointing, Clean };
inline constexpr double kCleanSupport = 0.9;
CaptureQuality capture_quality(const Detection& d);

class MotionDetector {
public:
    // Throws std::invalid_argument on invalid parameters.
    explicit MotionDetector(const DetectionParams& params = {});

    // Compares `bgr` (CV_8UC3) with the previous frame given; returns the hand when a
    // moving skin-coloured blob is found. The first frame, or one whose size changed, only
    // primes the detector. Throws std::invalid_argument on an empty or non-BGR frame.
    // With `segment` false only the frame difference and the motion history are updated
    // (cheap), and nullopt is returned: for watching the hand between full detections.
    // `static_scene` (CV_8UC1 of the frame's size, or empty): pixels known to show the
    // static scene, which are not the hand whatever their colour; another size throws.
    std::optional<Detection> process(const cv::Mat& bgr, const SkinModel& prior = SkinModel::generic(),
                                     bool segment = true, const cv::Mat1b& static_scene = {});

    // process() in two steps: the frame difference and motion history (true when the frame
    // changed enough to look for a hand in), then the segmentation of that frame.
    bool difference(const cv::Mat& bgr);
    std::optional<Detection> segment_last(const cv::Mat& bgr, const SkinModel& prior = SkinModel::generic(),
                                          const cv::Mat1b& static_scene = {}) const;
    // Pixels of the last difference that changed outside `box`.
    int changed_outside(const cv::Rect& box) const;
    // The least change process() looks for a hand in.
    int min_changed_pixels() const { return p_.min_changed_pixels; }
    // Forgets the frames seen; the next one only primes the detector. Its buffers are kept,
    // so a tracker that rests the detector and feeds it again allocates nothing.
    void reset();

    // Non-zero where the image changed in the last history_frames frames (the frames'
    // size; empty before the first frame and after a reset).
    const cv::Mat1b& recent_motion() const;

private:
    DetectionParams p_;
    cv::Mat1b previous_, grey_, changed_;
    cv::Mat1b history_;      // frames since each pixel last changed, counting down to 0
    int motion_frames_ = 0;  // consecutive frames with motion
    bool primed_ = false;    // previous_ holds the last frame seen
};

// Three standard deviations of the noise in an absolute frame difference (CV_8UC1),
// rounded up (0.3 % of the noise exceeds it); 0 for an empty one. Estimated from the lower
// quartile of every 16th pixel (half normal: the quartile is 0.3186 sigma), taken again
// without the pixels above the first estimate, which really changed.
int frame_noise_threshold(const cv::Mat1b& difference);

// The part of detection after the motion box: learns the skin colour of the `moving` pixels
// (CV_8UC1, frame-sized) inside `box`, segments the frame with it and returns the skin
// component that holds the most moving pixels, or nullopt. When `recent_motion` (pixels
// that changed in the last frames) is given and much of the component lies far from it,
// the component is cut to within `history_reach` of it when `history_mature` (motion was
// seen for history_frames frames), and rejected otherwise: a static face or object of skin
// colour that the hand touches is not part of the hand. Pixels of `static_scene` (frame-
// sized, or empty) are not skin: a known static background is cut off exactly, and a
// component it was cut off (more than 1 % of its area within 2 px) is marked `cut`.
std::optional<Detection> segment_hand(const cv::Mat& bgr, const cv::Mat1b& moving, const cv::Rect& box,
                                      const SkinModel& prior, const DetectionParams& params,
                                      const cv::Mat1b& recent_motion = {}, bool history_mature = true,
                                      const cv::Mat1b& static_scene = {});

}  // namespace gc
