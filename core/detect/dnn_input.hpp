// The input blob both hand models take: one RGB image, planar, scaled to the model's range.
#pragma once

#include <opencv2/core.hpp>

namespace gc {

// A 1x3xSxS float blob for a square input of side S.
cv::Mat make_square_blob(int side);

// Writes the square BGR image `bgr` into `blob` (from make_square_blob of its side) as planar
// RGB, each value v mapped to v * scale + shift. `scratch` is reused between calls.
void fill_rgb_blob(const cv::Mat3b& bgr, double scale, double shift, cv::Mat3f& scratch, cv::Mat& blob);

// The gain that brings a dark image's bright end (the 95th percentile of its grey levels,
// below kDarkBrightEnd) up to kExposedBrightEnd, at most kMaxDarkGain; 1 for an image that
// is not dark. Pixels at kBlownOutLevel and above are left out of the percentile. `grey` is
// reused between calls.
constexpr int kBlownOutLevel = 250;
constexpr int kDarkBrightEnd = 100;
constexpr int kExposedBrightEnd = 170;
constexpr double kMaxDarkGain = 3.0;
double dark_image_gain(const cv::Mat3b& bgr, cv::Mat1b& grey);

// Scales `bgr` in place by dark_image_gain (saturating at 255): a dark picture shown to the
// models at a normal exposure. Nothing changes when the gain is 1.
void brighten_if_dark(cv::Mat3b& bgr, cv::Mat1b& grey);

}  // namespace gc
