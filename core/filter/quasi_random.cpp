#include "filter/quasi_random.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace gc {

namespace {

constexpr std::array<unsigned, QuasiNormalSampler::kMaxDims> kPrimes{2, 3, 5, 7, 11, 13, 17, 19};
constexpr int kTableSize = 8192;
constexpr double kTailZ = 4.2;

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// z at p = k / kTableSize for k = 0..kTableSize, by bisection on the exact CDF (built once).
const std::vector<double>& quantile_table()
{
    static const std::vector<double> table = [] {
        std::vector<double> t(kTableSize + 1);
        for (int k = 0; k <= kTableSize; ++k) {
            const double p = double(k) / kTableSize;
            double lo = -kTailZ, hi = kTailZ;
            for (int it = 0; it < 60; ++it) {
                const double mid = 0.5 * (lo + hi);
                (normal_cdf(mid) < p ? lo : hi) = mid;
            }
            t[k] = 0.5 * (lo + hi);
        }
        return t;
    }();
    return table;
}

// Linear interpolation in `table` (quantile_table()); p is clamped to (0, 1).
inline double interpolate_quantile(const double* table, double p)
{
    if (!(p > 0.0)) return -kTailZ;  // also catches NaN
    if (p >= 1.0) return kTailZ;
    const double f = p * kTableSize;
    const int k = std::min(static_cast<int>(f), kTableSize - 1);
    const double a = f - k;
    return table[k] * (1.0 - a) + table[k + 1] * a;
}

}  // namespace

double inverse_normal_cdf(double p) { return interpolate_quantile(quantile_table().data(), p); }

namespace {

// The digits of `index`, least significant first, mirrored about the point. `Base` is
// either unsigned or a std::integral_constant: with the base a constant the divisions
// compile to multiplications, and this runs for every particle and dimension of a frame.
template <typename Base>
double mirrored_digits(std::uint64_t index, Base base)
{
    const double inv = 1.0 / static_cast<unsigned>(base);
    double scale = inv, result = 0.0;
    while (index > 0) {
        result += static_cast<double>(index % base) * scale;
        index /= base;
        scale *= inv;
    }
    return result;
}

template <unsigned B>
using ConstantBase = std::integral_constant<unsigned, B>;

// Calls f(base) with the base as a std::integral_constant when it is one of the sampler's
// (kPrimes), else as a plain unsigned.
template <typename F>
decltype(auto) with_constant_base(unsigned base, F&& f)
{
    switch (base) {
    case 2:
        return f(ConstantBase<2>{});
    case 3:
        return f(ConstantBase<3>{});
    case 5:
        return f(ConstantBase<5>{});
    case 7:
        return f(ConstantBase<7>{});
    case 11:
        return f(ConstantBase<11>{});
    case 13:
        return f(ConstantBase<13>{});
    case 17:
        return f(ConstantBase<17>{});
    case 19:
        return f(ConstantBase<19>{});
    default:
        return f(base);
    }
}

}  // namespace

double radical_inverse(std::uint64_t index, unsigned base)
{
    return with_constant_base(base, [index](auto b) { return mirrored_digits(index, b); });
}

QuasiNormalSampler::QuasiNormalSampler(int dims, std::uint64_t seed) : dims_(dims), rng_(seed)
{
    if (dims < 1 || dims > kMaxDims)
        throw std::invalid_argument("QuasiNormalSampler: dims must be in [1, " + std::to_string(kMaxDims) + "]");
    quantile_table();  // build outside the first frame
}

void QuasiNormalSampler::next_frame(std::span<double> out)
{
    if (out.size() % static_cast<std::size_t>(dims_) != 0)
        throw std::invalid_argument("QuasiNormalSampler: output size not a multiple of dims");
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::array<double, kMaxDims> shift{};
    for (int d = 0; d < dims_; ++d) shift[d] = unit(rng_);
    // A random start each frame: continuing the sequence would hand slot i points with
    // the same leading digits frame after frame (when the count has factors of the base),
    // and the noise of a particle lineage would add up coherently.
    const std::uint64_t start = 1 + (rng_() >> 44);  // at most 2^20: few digits to compute
    const std::size_t count = out.size() / dims_;
    const double* table = quantile_table().data();
    // One dimension at a time, so that its base is a constant in the inner loop.
    for (int d = 0; d < dims_; ++d)
        with_constant_base(kPrimes[d], [&](auto base) {
            for (std::size_t i = 0; i < count; ++i) {
                double u = mirrored_digits(start + i, base) + shift[d];
                if (u >= 1.0) u -= 1.0;
                out[i * dims_ + d] = interpolate_quantile(table, u);
            }
        });
}

}  // namespace gc
