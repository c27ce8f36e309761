// Low-discrepancy Gaussian noise for the dynamics: consecutive points of a Halton sequence
// (one prime base per state dimension) from a random start, randomly shifted modulo 1
// (Cranley-Patterson rotation; frames differ but stay reproducible from the seed), mapped
// through the inverse normal CDF. Copies of one resampled ancestor take consecutive points, which
// spread evenly over the noise space instead of clumping as pseudo-random draws do.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>

namespace gc {

// The inverse of the standard normal CDF, from a table (no transcendental call), accurate
// to ~1e-4 in the body and clamped to +-4.2 in the tails. p is clamped to (0, 1).
double inverse_normal_cdf(double p);

// The radical inverse of `index` in base `base`: the Halton coordinate in [0, 1).
double radical_inverse(std::uint64_t index, unsigned base);

class QuasiNormalSampler {
public:
    static constexpr int kMaxDims = 8;

    // Throws std::invalid_argument unless 1 <= dims <= kMaxDims.
    QuasiNormalSampler(int dims, std::uint64_t seed);

    // Fills out[i * dims + d] with standard normal deviates for points i = 0 .. count-1
    // of this frame's rotated sequence; out.size() must be a multiple of dims.
    void next_frame(std::span<double> out);

private:
    int dims_;
    std::mt19937_64 rng_;
};

}  // namespace gc
