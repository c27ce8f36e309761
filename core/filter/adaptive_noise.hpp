// The process noise of the zero-order dynamics X_t + C_t = X_{t-1} + C_{t-1} + B_t w_t,
// adapted as the thesis does: B_t = K B_{t-1}, K the ratio of the last two compensated
// displacements (the spread grows while the hand accelerates and shrinks as it slows).
// K is clamped, and B is kept within [min, max] and never below a fraction of the last
// displacement, which a zero-order model must cover to follow a moving hand at all.
#pragma once

#include <array>

namespace gc {

// Components: x, y (pixels), rotation (radians), log-scale.
using NoiseVector = std::array<double, 4>;

struct AdaptiveNoiseParams {
    NoiseVector initial{4.0, 4.0, 0.05, 0.03};
    NoiseVector minimum{1.5, 1.5, 0.02, 0.012};
    NoiseVector maximum{25.0, 25.0, 0.25, 0.12};
    NoiseVector epsilon{1.0, 1.0, 0.01, 0.006};  // keeps K finite for a still hand
    double k_min = 0.5;
    double k_max = 2.0;
    double cover = 0.7;  // B >= cover * |last displacement|
};

class AdaptiveNoise {
public:
    // Throws std::invalid_argument on non-positive or inconsistent parameters.
    explicit AdaptiveNoise(const AdaptiveNoiseParams& params = {});

    void reset();
    // Feeds the latest compensated displacement (X_t + C_t) - (X_{t-1} + C_{t-1}).
    void update(const NoiseVector& displacement);
    const NoiseVector& sigma() const { return sigma_; }

private:
    AdaptiveNoiseParams p_;
    NoiseVector sigma_;
    NoiseVector last_;
    bool have_last_ = false;
};

}  // namespace gc
