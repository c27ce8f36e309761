// Shared value types of the tracker: the 2D hand state, per-eye estimates, the head pose.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <string_view>
#include <vector>

namespace gc {

enum class Eye { Left = 0, Right = 1 };

// X_t = (x, y, r, s): the position in pixels of the template origin (the palm centre),
// the in-plane rotation in radians (image axes: x right, y down, so positive is clockwise
// on screen) and the scale relative to the template captured at initialisation.
// `squash` is the template's shape rather than its pose: the outline's horizontal
// foreshortening relative to the capture (the hand turned about the vertical axis, as
// when pointing at someone else around a table, narrows in the image by the cosine of the
// turn). The tracker estimates it from the edges and applies it to every hypothesis.
struct HandState {
    double x = 0.0;
    double y = 0.0;
    double rotation = 0.0;
    double scale = 1.0;
    double squash = 1.0;
};

// C_t of the dynamics: how the head's motion between two frames moves a static hand in the
// image (pixels, radians, and a multiplicative scale change, 1 = none).
struct ImageMotion {
    double dx = 0.0;
    double dy = 0.0;
    double drotation = 0.0;
    double scale_factor = 1.0;

    // False for no motion and for a motion of rounding residue only (1e-14 px from poses
    // composed and inverted), which moves no pixel.
    bool moves() const;
};

enum class TrackState { Acquiring, Tracking, Lost };

std::string_view to_string(TrackState s);

// What the hand does, from its 21 key points. Unknown where no key points are known (the
// motion-only detector, which assumes the thesis's pointing hand).
enum class Gesture { Unknown, Pointing, Open, Fist, Other };

std::string_view to_string(Gesture g);

// What one eye's tracker reports for one frame; the JSON "left"/"right" objects.
struct EyeEstimate {
    TrackState state = TrackState::Acquiring;
    HandState mean;                    // weighted mean of the particles
    HandState best;                    // the highest-weight hypothesis
    double confidence = 0.0;           // best likelihood / P_init, clamped to [0, 1]
    cv::Rect bbox;                     // of the estimated contour, image pixels
    std::vector<cv::Point2f> contour;  // closed polygon of the estimated contour
    cv::Point2f fingertip;             // index fingertip, image pixels
    cv::Point2f palm;                  // palm centre, image pixels
    double pointing_deg = 0.0;         // palm -> fingertip, 0 = +x, counter-clockwise, y up
    Gesture gesture = Gesture::Unknown;
    std::vector<cv::Point2f> landmarks;  // the 21 key points, or none (motion-only detector)
    bool models_ran = false;             // the learned models looked at this frame
    bool valid() const { return state == TrackState::Tracking; }
    // Whether this estimate may say where the hand points: a tracked hand whose gesture is
    // pointing, or unknown (the motion-only detector tracks a pointing hand by design).
    bool pointing() const { return valid() && (gesture == Gesture::Pointing || gesture == Gesture::Unknown); }
};

// The motorised head: pan (neck), tilt, and each eye's vergence, in degrees.
// Sign conventions (OpenCV camera frame: x right, y down, z forward):
//   pan > 0 turns the head to the right (rotation about +y),
//   tilt > 0 looks up (rotation about +x),
//   vergence > 0 turns that eye to the right; converging eyes: left > 0, right < 0.
struct HeadPose {
    double pan_deg = 0.0;
    double tilt_deg = 0.0;
    double verge_left_deg = 0.0;
    double verge_right_deg = 0.0;
    // Optical magnification of both eyes' zoom lenses: 1 is the calibrated (widest) field of
    // view, 2 halves it. The focal length in pixels scales by this factor.
    double zoom = 1.0;

    friend bool operator==(const HeadPose&, const HeadPose&) = default;
};

}  // namespace gc
