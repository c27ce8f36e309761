#include "filter/adaptive_noise.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

AdaptiveNoise::AdaptiveNoise(const AdaptiveNoiseParams& params) : p_(params)
{
    for (int d = 0; d < 4; ++d)
        if (!(p_.minimum[d] > 0.0 && p_.minimum[d] <= p_.initial[d] && p_.initial[d] <= p_.maximum[d] &&
              p_.epsilon[d] > 0.0))
            throw std::invalid_argument("AdaptiveNoise: need 0 < minimum <= initial <= maximum "
                                        "and epsilon > 0 in every component");
    if (!(p_.k_min > 0.0 && p_.k_min <= 1.0 && p_.k_max >= 1.0 && p_.cover >= 0.0))
        throw std::invalid_argument("AdaptiveNoise: need 0 < k_min <= 1 <= k_max, cover >= 0");
    reset();
}

void AdaptiveNoise::reset()
{
    sigma_ = p_.initial;
    last_ = {};
    have_last_ = false;
}

void AdaptiveNoise::update(const NoiseVector& displacement)
{
    for (int d = 0; d < 4; ++d) {
        const double now = std::abs(displacement[d]);
        if (have_last_) {
            const double k =
                std::clamp((now + p_.epsilon[d]) / (std::abs(last_[d]) + p_.epsilon[d]), p_.k_min, p_.k_max);
            sigma_[d] *= k;
        }
        sigma_[d] = std::clamp(std::max(sigma_[d], p_.cover * now), p_.minimum[d], p_.maximum[d]);
    }
    last_ = displacement;
    have_last_ = true;
}

}  // namespace gc
