// The tracker on a real calibrated stereo recording with reference key points (the pair in
// tests/data/handpose3d: two cameras 0.5 m apart, a hand pointing in frames 14-212): how far
// each view's fingertip is from the reference, how often a 3D ray comes out and at what
// angle to the reference's, how often pointing is claimed where the hand does not point,
// and what a frame costs. Shared by gesturecam-bench and the regression test.
#pragma once

#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace gc::tools {

struct RealPairOptions {
    std::string dir;      // holds handpose3d_cam{0,1}.mp4, *.mediapipe.json, _ref3d.json, _calib.yml
    int first_frame = 0;  // frames [first_frame, last_frame) are tracked
    int last_frame = 1 << 30;
    TrackerParams params;
    // Camera noise added to every decoded frame of both views: the rendered scenes' Gaussian
    // sensor noise (sim::SensorNoise), this standard deviation in grey levels (0: the
    // recording as it is). The same every run.
    double noise_sd = 0.0;
    // A dim room through a camera that keeps its settings, below 1: each grey level v of
    // both views becomes 255 * dim * (v / 255)^2.2 (darker, the shadows crushed), before the
    // noise. 1: the recording as it is.
    double dim = 1.0;
    // A window in view that the camera's exposure cannot hold: kBrightWindows, set to white
    // in both views after the dimming and before the noise. The hand never goes there.
    bool bright_window = false;
};

// Where the bright window lies in the pair's 720x720 frames: the left view's shelf and floor
// beside the desk, the right view's wall above it.
inline const cv::Rect kBrightWindows[2] = {{0, 0, 180, 300}, {180, 0, 290, 120}};

struct ViewFigures {
    int reference_frames = 0;         // frames where the reference has the hand in this view
    double coverage = 0.0;            // share of them with a tracked fingertip
    double within_30px = 0.0;         // share of them with the fingertip within 30 px of the reference
    double median_px = 0.0;           // fingertip error, over the covered frames
    double median_px_models = 0.0;    // ... on frames where the learned models ran
    double median_px_carried = 0.0;   // ... on frames the contour carried alone
    double models_share = 0.0;        // share of tracked frames where the models ran
    int pointing_frames = 0;          // reference pointing frames with the hand in this view
    double pointing_coverage = 0.0;   // share of them with a tracked fingertip
    double pointing_median_px = 0.0;  // fingertip error over those
};

struct RealPairFigures {
    int frames = 0;
    ViewFigures left, right;
    int pointing_frames = 0;    // reference frames where the hand points (3D reference)
    double ray_coverage = 0.0;  // share of them with a 3D ray
    double angle_median_deg = 0.0;
    double angle_p90_deg = 0.0;
    int other_frames = 0;           // reference frames where it does not point
    double false_pointing = 0.0;    // share of them with a 3D ray
    double ms_per_frame = 0.0;      // median wall time of one stereo frame
    double cpu_ms_per_frame = 0.0;  // median CPU time of one, every thread of the process
};

// A camera that moves while it films (held in the hand or worn): the window's centre wanders
// slowly and bobs faster, as on a walk, and the window turns about its centre. Amplitudes
// in the recording's pixels and in degrees; all zero keeps the window still.
struct CameraSway {
    double drift_px = 0.0;
    double bob_px = 0.0;
    double roll_deg = 0.0;
    bool still() const { return drift_px == 0.0 && bob_px == 0.0 && roll_deg == 0.0; }
};

// One view of the pair seen through a narrower camera: a window of its frames scaled to
// `size`, so that the hand enters from the window's edge (wrist or palm cut off) as it does
// before a webcam close to the speaker. The view is tracked alone and scored against the
// reference key points carried into the window.
struct RealCropOptions {
    std::string dir;  // as RealPairOptions::dir
    int camera = 0;   // 0: handpose3d_cam0 (left), 1: cam1 (right)
    cv::Rect window;  // in the recording's 720x720 frames; where a swaying window is centred
    CameraSway sway;
    cv::Size size{640, 480};
    int first_frame = 0;
    int last_frame = 1 << 30;
    TrackerParams params;
    double noise_sd = 0.0;  // as RealPairOptions::noise_sd, added to the window's frames
    double dim = 1.0;       // as RealPairOptions::dim
};

// A frame counts when the reference fingertip and at least half of its key points lie in
// the window; `cut_frames` of those have key points outside it.
struct RealCropFigures {
    ViewFigures view;
    int cut_frames = 0;
};

// The windows gesturecam-bench reports: the hand entering from the top of the left view
// (its wrist cut on most frames), from the left of the right view (a closer camera: the
// window is scaled up 1.7x), the left view with the fingertip near the right edge, and the
// left view through a moving camera (up to 11 px of motion per frame and 4 deg of
// roll; the hand crosses the top edge as the window moves).
struct NamedWindow {
    const char* name;
    int camera;
    cv::Rect window;
    CameraSway sway{};
};
inline const NamedWindow kEdgeWindows[] = {{"cam0 from the top", 0, {80, 180, 640, 480}},
                                           {"cam1 from the left, closer", 1, {330, 220, 380, 285}},
                                           {"cam0 towards the right", 0, {0, 100, 640, 480}},
                                           {"cam0, a moving camera", 0, {80, 150, 560, 420}, {40.0, 12.0, 4.0}}};

// Options that track `window` of the pair in `dir`, every other option at its default.
RealCropOptions window_options(const std::string& dir, const NamedWindow& window);

// MediaPipe's 21 key points of one frame of a view, in pixels; nothing where it found no hand.
using ReferenceHand = std::optional<std::array<cv::Point2d, 21>>;

// The reference key points of one view (`path`: handpose3d_camN.mediapipe.json), frame i at
// index i. Throws std::runtime_error on a missing or unreadable file.
std::vector<ReferenceHand> read_reference_hands(const std::string& path);

// Decodes both recordings (frame i = the i-th decoded frame), tracks them in stereo and
// scores the result. Throws std::runtime_error on missing or unreadable files.
RealPairFigures measure_real_pair(const RealPairOptions& options);

// Decodes one recording, tracks the window of each frame and scores it. Throws
// std::runtime_error on missing or unreadable files, std::invalid_argument on a window
// outside the frame.
RealCropFigures measure_real_crop(const RealCropOptions& options);

}  // namespace gc::tools
