// The tracking overlay of handtracker's `draw` and of handoverlay: the tracked contour, the
// particles' marginal distributions along the frame borders (x along the bottom, y along the
// right edge, as in the thesis's figures), the pointing direction, the state and the gesture,
// drawn with OpenCV on a BGR image.
#pragma once

#include "stereo/pointing.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>

#include <span>
#include <vector>

namespace gc::gst {

class TrackingOverlay {
public:
    // `particles` may be empty (no distribution to show); `pointing` may be null.
    void draw(cv::Mat& bgr, const EyeEstimate& eye, std::span<const Particle> particles, const Pointing3D* pointing);

private:
    void draw_marginals(cv::Mat& bgr, std::span<const Particle> particles);
    std::vector<double> x_bins_;
    std::vector<double> y_bins_;
    std::vector<cv::Point> polygon_;
};

}  // namespace gc::gst
