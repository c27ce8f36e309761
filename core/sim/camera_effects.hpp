// What a real camera adds to the light that reaches it, for the wide variety: darker image
// corners, the smear of a hand moving while the shutter is open, and lossy compression.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace gc::sim {

// Per-pixel gains (CV_16UC3, 256 = unchanged) of a lens that loses `strength` of the light
// in the image corners, falling off with the square of the distance from the centre.
cv::Mat vignetting_gains(cv::Size size, double strength);
// bgr (CV_8UC3) times the gains.
void apply_vignetting(cv::Mat& bgr, const cv::Mat& gains);

// A normalised line kernel (CV_32F) that smears by `motion` pixels (centred on it).
cv::Mat motion_kernel(cv::Point2d motion);

// Composites `layer` (CV_8UC3, times `gain`) with its coverage (CV_8U, 255 = opaque) over
// `target` (all of one size) through a motion kernel: the layer's light and its coverage
// are both smeared, then target = light + (1 - coverage) * target.
void composite_smeared(cv::Mat& target, const cv::Mat& layer, const cv::Mat& coverage, float gain,
                       const cv::Mat& kernel);

// Gaussian sensor noise (CV_8UC3 frames): a pool larger than the frame by kMargin, drawn
// once from `seed`, of which each frame takes the window at an offset hashed from `where`.
// The pool is kept as its positive part and its negated negative part, so that two
// saturating 8-bit passes apply it.
class SensorNoise {
public:
    static constexpr int kMargin = 64;  // 64 x 64 distinct offsets

    SensorNoise() = default;  // no noise
    SensorNoise(cv::Size frame, double sigma, std::uint64_t seed);
    void apply(cv::Mat& bgr, std::uint64_t where) const;

private:
    cv::Mat up_, down_;
};

// Encodes as JPEG of the given quality (4:2:0 chroma) and decodes back into `bgr`.
void jpeg_round_trip(cv::Mat& bgr, int quality);

}  // namespace gc::sim
