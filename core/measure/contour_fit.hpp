// Refinement of one hypothesis against the image ("refine the best contour"): a few
// Gauss-Newton steps of a weighted least-squares fit of the similarity transform
// (x, y, rotation, scale) to the skin edges found along the dense outline's normals
// (point-to-line distances, which are linear in a = s cos r, b = s sin r, x, y), and
// optionally of the squash (HandState::squash), linearised about its current value.
#pragma once

#include "common/types.hpp"
#include "contour/hand_template.hpp"

#include <opencv2/core.hpp>

namespace gc {

inline constexpr double kAgreementPx = 1.5;

struct FitParams {
    int iterations = 4;
    double half_window = 5.0;   // pixels searched either side of the current contour
    double step = 0.5;          // bilinear sampling step along a normal
    double robust_scale = 1.5;  // pixels: Cauchy weight 1 / (1 + (d / scale)^2)
    double min_found = 0.5;     // fraction of the outline's normals that must find an edge
    // Fit the squash too, by at most max_squash_step per call (relative) and within
    // [min_squash, max_squash]. Off: the start's squash is kept.
    bool fit_squash = false;
    double max_squash_step = 0.04;
    double min_squash = 0.5;
    double max_squash = 1.5;
};

struct FitResult {
    HandState state;
    double found_fraction = 0.0;  // of the last iteration
    double rms_px = 0.0;          // weighted RMS distance to the edges found, last iteration
    // Fraction (outline weights) of the normals whose edge lies within kAgreementPx of the
    // contour at the last iteration: how much of the template's outline the image shows.
    double agreement = 0.0;
    bool converged = false;  // false: too few edges, the input state is returned
};

// With `bgr` (the frame the membership map was computed from), each edge found is moved
// to where the colour is halfway between skin and background (colour_edge_offset).
FitResult refine_fit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& start,
                     const FitParams& params = {}, const cv::Mat& bgr = {});

}  // namespace gc
