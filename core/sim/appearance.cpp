#include "sim/appearance.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace gc::sim {

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream)
{
    // splitmix64 finaliser over the pair: nearby seeds give unrelated streams.
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

cv::Vec3f pick_skin_tone(Rng& rng)
{
    // BGR of lit skin as typical webcams record it, fair to dark.
    static constexpr std::array<std::array<float, 3>, 6> kTones{{
        {150.f, 172.f, 222.f},
        {128.f, 158.f, 214.f},
        {108.f, 142.f, 198.f},
        {88.f, 122.f, 178.f},
        {66.f, 94.f, 142.f},
        {50.f, 73.f, 112.f},
    }};
    const auto& t = kTones[std::uniform_int_distribution<std::size_t>(0, kTones.size() - 1)(rng)];
    // A few per cent of individual variation in brightness and redness.
    const float gain = float(uniform(rng, 0.92, 1.06));
    const float red = float(uniform(rng, 0.98, 1.03));
    return {t[0] * gain, t[1] * gain, std::min(250.f, t[2] * gain * red)};
}

cv::Vec3f skin_like_colour(Rng& rng, const cv::Vec3f& skin, double sum_lo, double sum_hi)
{
    const double s = skin[0] + skin[1] + skin[2];
    double r = skin[2] / s + uniform(rng, -0.006, 0.006);
    double g = skin[1] / s + uniform(rng, -0.003, 0.003);
    const double b = 1.0 - r - g;
    double sum = uniform(rng, sum_lo, sum_hi);
    sum = std::min(sum, 250.0 / r);  // keep the red channel unsaturated
    return {float(b * sum), float(g * sum), float(r * sum)};
}

cv::Vec3f non_skin_colour(Rng& rng, double value_lo, double value_hi, double saturation_max)
{
    const double v = uniform(rng, value_lo, value_hi) * 255.0;
    if (uniform(rng, 0.0, 1.0) < 0.35) return {float(v), float(v), float(v)};
    // Hues from green (90 deg) through cyan and blue to violet (290 deg): red never
    // dominates, so neither these colours nor their blends with grey look like skin.
    const double hue = uniform(rng, 90.0, 290.0);
    const double sat = uniform(rng, 0.1 * saturation_max, saturation_max);
    const double c = v * sat;
    const double hp = hue / 60.0;
    const double x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
    double r = 0, g = 0, b = 0;
    if (hp < 2.0) {
        r = x;
        g = c;
    } else if (hp < 3.0) {
        g = c;
        b = x;
    } else if (hp < 4.0) {
        g = x;
        b = c;
    } else {
        r = x;
        b = c;
    }
    const double m = v - c;
    return {float(b + m), float(g + m), float(r + m)};
}

cv::Scalar to_scalar(const cv::Vec3f& bgr, double gain)
{
    return {std::clamp(bgr[0] * gain, 0.0, 255.0), std::clamp(bgr[1] * gain, 0.0, 255.0),
            std::clamp(bgr[2] * gain, 0.0, 255.0)};
}

cv::Mat1f smooth_noise(cv::Size size, double cell, cv::RNG& rng)
{
    const int w = std::max(2, int(std::ceil(size.width / cell)) + 1);
    const int h = std::max(2, int(std::ceil(size.height / cell)) + 1);
    cv::Mat1f coarse(h, w);
    rng.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
    cv::Mat1f fine;
    cv::resize(coarse, fine, size, 0, 0, cv::INTER_CUBIC);
    return fine;
}

void modulate(cv::Mat3b& image, const cv::Mat1f& pattern, double amplitude, const cv::Mat1b& mask)
{
    CV_Assert(pattern.size() == image.size());
    for (int y = 0; y < image.rows; ++y) {
        cv::Vec3b* p = image.ptr<cv::Vec3b>(y);
        const float* q = pattern.ptr<float>(y);
        const std::uint8_t* m = mask.empty() ? nullptr : mask.ptr<std::uint8_t>(y);
        for (int x = 0; x < image.cols; ++x) {
            if (m && !m[x]) continue;
            const float k = 1.0f + float(amplitude) * q[x];
            for (int c = 0; c < 3; ++c) p[x][c] = cv::saturate_cast<std::uint8_t>(p[x][c] * k);
        }
    }
}

}  // namespace gc::sim
