// The generic core of factored sampling, independent of what a state is: weight
// normalisation, systematic resampling and the effective sample size. The hand tracker and
// the tests' linear-Gaussian model both run on these.
#pragma once

#include <cstdint>
#include <span>

namespace gc {

// Turns log-weights into normalised weights in place (subtracting the maximum first, so
// very small likelihoods do not underflow). Returns the log of the mean unnormalised
// weight: log((1/N) sum exp(l_i)). Throws std::invalid_argument on an empty span or a
// NaN; -inf entries are allowed and become 0, but not all of them.
double normalise_log_weights(std::span<double> log_weights);

// Systematic resampling in O(N): one uniform offset u0 in [0, 1), then ancestors at the
// strata (u0 + k) / N of the cumulative weights. `weights` must be normalised; `ancestors`
// receives ancestors.size() indices into weights, in non-decreasing order. Throws
// std::invalid_argument on empty spans or u0 outside [0, 1).
void systematic_resample(std::span<const double> weights, double u0, std::span<std::uint32_t> ancestors);

// 1 / sum w_i^2 of normalised weights: N for equal weights, 1 when one particle holds all.
double effective_sample_size(std::span<const double> weights);

}  // namespace gc
