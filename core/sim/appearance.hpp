// Colours and surface textures of the scene: realistic skin tones, skin-like materials
// (wood, cardboard, beige) of the same chromaticity, clearly non-skin materials, and the
// luminance patterns that texture them without changing their chromaticity.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <random>

namespace gc::sim {

using Rng = std::mt19937_64;

// Independent, reproducible seeds for the parts of a scene (layout, hand, motion, noise).
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream);

double uniform(Rng& rng, double lo, double hi);

// A skin tone under the scene's white light, BGR 0..255: R > G > B with normalised
// r ~ 0.40-0.48 and g ~ 0.31-0.32, from fair to dark.
cv::Vec3f pick_skin_tone(Rng& rng);

// A material of (nearly) the chromaticity of `skin` with channel sum in [sum_lo, sum_hi]:
// what a skin-colour filter cannot tell from skin.
cv::Vec3f skin_like_colour(Rng& rng, const cv::Vec3f& skin, double sum_lo, double sum_hi);

// A colour far from any skin chromaticity: a hue between green and violet, or a neutral
// grey, with HSV value in [value_lo, value_hi] and saturation at most saturation_max.
cv::Vec3f non_skin_colour(Rng& rng, double value_lo, double value_hi, double saturation_max = 0.75);

cv::Scalar to_scalar(const cv::Vec3f& bgr, double gain = 1.0);

// Smooth random field of the given size, mean 0 and standard deviation ~1, with features
// about `cell` pixels across.
cv::Mat1f smooth_noise(cv::Size size, double cell, cv::RNG& rng);

// Multiplies every channel of `image` by (1 + amplitude * pattern) inside `mask` (all of
// it when the mask is empty): brightness only, chromaticity unchanged.
void modulate(cv::Mat3b& image, const cv::Mat1f& pattern, double amplitude, const cv::Mat1b& mask = cv::Mat1b());

}  // namespace gc::sim
