#include "filter/resampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gc {

double normalise_log_weights(std::span<double> log_weights)
{
    if (log_weights.empty()) throw std::invalid_argument("normalise_log_weights: no weights");
    double top = -std::numeric_limits<double>::infinity();
    for (double l : log_weights) {
        if (std::isnan(l) || l == std::numeric_limits<double>::infinity())
            throw std::invalid_argument("normalise_log_weights: NaN or +inf log-weight");
        top = std::max(top, l);
    }
    if (top == -std::numeric_limits<double>::infinity())
        throw std::invalid_argument("normalise_log_weights: every weight is zero");
    double sum = 0.0;
    for (double& l : log_weights) {
        l = std::exp(l - top);
        sum += l;
    }
    for (double& w : log_weights) w /= sum;
    return top + std::log(sum / static_cast<double>(log_weights.size()));
}

void systematic_resample(std::span<const double> weights, double u0, std::span<std::uint32_t> ancestors)
{
    if (weights.empty() || ancestors.empty())
        throw std::invalid_argument("systematic_resample: empty weights or output");
    if (!(u0 >= 0.0 && u0 < 1.0)) throw std::invalid_argument("systematic_resample: offset must be in [0, 1)");
    const std::size_t n = ancestors.size();
    const std::size_t last = weights.size() - 1;
    const double step = 1.0 / static_cast<double>(n);
    double target = u0 * step;
    double cumulative = weights[0];
    std::size_t i = 0;
    for (std::size_t k = 0; k < n; ++k) {
        // Rounding may leave the cumulative sum a hair below 1: never run past the end.
        while (cumulative <= target && i < last) cumulative += weights[++i];
        ancestors[k] = static_cast<std::uint32_t>(i);
        target += step;
    }
}

double effective_sample_size(std::span<const double> weights)
{
    double s2 = 0.0;
    for (double w : weights) s2 += w * w;
    return s2 > 0.0 ? 1.0 / s2 : 0.0;
}

}  // namespace gc
