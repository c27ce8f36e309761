// Tracking wide frames at a smaller size: the size the tracker works at, the calibration
// for it, and the way back from its pixels to the frame's.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>

#include <span>
#include <vector>

namespace gc {

// The frames' size and the smaller one the tracker sees them at.
struct AnalysisScale {
    cv::Size frame;
    cv::Size analysed;
    double sx = 1.0;  // analysed / frame, per axis (the height is rounded to whole pixels)
    double sy = 1.0;

    bool active() const { return analysed != frame; }
};

inline constexpr int kMinTrackingWidth = 64;
inline constexpr int kMinTrackingHeight = 32;

// Frames wider than `max_width` (at least kMinTrackingWidth) are analysed at that width,
// their aspect kept, and never below kMinTrackingHeight lines; `max_width` 0 (or a frame no
// wider) leaves them as they are.
AnalysisScale analysis_scale(cv::Size frame, int max_width);

// Scratch images for downscale(), kept from frame to frame so that it allocates nothing
// once their sizes are set.
struct DownscaleBuffers {
    cv::Mat halves[2];
};

// `frame` at `to` (no larger): halved by pixel averaging while it is at least twice as large,
// then linearly interpolated the rest of the way (less than twice). Averaging by the whole
// factor (OpenCV's INTER_AREA) costs five times as much at factors between 2 and 4.
void downscale(const cv::Mat& frame, cv::Size to, DownscaleBuffers& buffers, cv::Mat& out);

// The calibration of the same cameras at the analysed size: focal lengths and principal
// point scaled (pixel centres kept at integer coordinates), the distortion's normalised
// coefficients and every millimetre unchanged.
StereoCalibration scaled_calibration(const StereoCalibration& calibration, const AnalysisScale& scale);

// The head's image motion in the frame's pixels, in the analysed ones.
ImageMotion to_analysed(const ImageMotion& motion, const AnalysisScale& scale);

// Every pixel quantity of an estimate made at the analysed size, in the frame's pixels; an
// estimate without a contour (none) is left alone.
void to_frame(EyeEstimate& estimate, const AnalysisScale& scale);

// The particles' positions in the frame's pixels, into `out` (its storage reused).
void to_frame(std::span<const Particle> particles, const AnalysisScale& scale, std::vector<Particle>& out);

}  // namespace gc
