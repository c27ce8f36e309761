#include "sim/camera_effects.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace gc::sim {

cv::Mat vignetting_gains(cv::Size size, double strength)
{
    cv::Mat gains(size, CV_16UC3);
    const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
    const double corner2 = cx * cx + cy * cy;
    for (int y = 0; y < size.height; ++y) {
        auto* g = gains.ptr<std::uint16_t>(y);
        for (int x = 0; x < size.width; ++x) {
            const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / corner2;
            const auto v = std::uint16_t(std::lround(256.0 * (1.0 - strength * r2)));
            g[3 * x] = g[3 * x + 1] = g[3 * x + 2] = v;
        }
    }
    return gains;
}

void apply_vignetting(cv::Mat& bgr, const cv::Mat& gains)
{
    CV_Assert(bgr.type() == CV_8UC3 && gains.type() == CV_16UC3 && bgr.size() == gains.size());
    const int n = bgr.cols * 3;
    for (int y = 0; y < bgr.rows; ++y) {
        std::uint8_t* p = bgr.ptr<std::uint8_t>(y);
        const std::uint16_t* g = gains.ptr<std::uint16_t>(y);
        for (int i = 0; i < n; ++i) p[i] = std::uint8_t((unsigned(p[i]) * g[i] + 128u) >> 8);
    }
}

cv::Mat motion_kernel(cv::Point2d motion)
{
    const double length = std::hypot(motion.x, motion.y);
    const int half = int(std::ceil(0.5 * length)) + 1;
    cv::Mat1f k(2 * half + 1, 2 * half + 1, 0.0f);
    const cv::Point2d c(half, half);
    constexpr int kShift = 4;
    auto fixed = [](cv::Point2d p) { return cv::Point(cvRound(p.x * 16.0), cvRound(p.y * 16.0)); };
    cv::line(k, fixed(c - 0.5 * motion), fixed(c + 0.5 * motion), cv::Scalar(1.0), 1, cv::LINE_AA, kShift);
    const double sum = cv::sum(k)[0];
    if (sum <= 0.0)
        k(half, half) = 1.0f;
    else
        k /= sum;
    return k;
}

void composite_smeared(cv::Mat& target, const cv::Mat& layer, const cv::Mat& coverage, float gain,
                       const cv::Mat& kernel)
{
    thread_local cv::Mat alpha, colour;
    coverage.convertTo(alpha, CV_32F, 1.0 / 255.0);
    layer.convertTo(colour, CV_32FC3, gain);
    cv::Mat planes[3];
    cv::split(colour, planes);
    for (cv::Mat& p : planes) p = p.mul(alpha);
    cv::merge(planes, 3, colour);
    cv::filter2D(colour, colour, -1, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
    cv::filter2D(alpha, alpha, -1, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
    for (int y = 0; y < target.rows; ++y) {
        cv::Vec3b* dst = target.ptr<cv::Vec3b>(y);
        const cv::Vec3f* src = colour.ptr<cv::Vec3f>(y);
        const float* a = alpha.ptr<float>(y);
        for (int x = 0; x < target.cols; ++x) {
            if (a[x] <= 0.0f) continue;
            const float keep = std::max(0.0f, 1.0f - a[x]);
            for (int c = 0; c < 3; ++c) dst[x][c] = cv::saturate_cast<std::uint8_t>(src[x][c] + keep * dst[x][c]);
        }
    }
}

void jpeg_round_trip(cv::Mat& bgr, int quality)
{
    thread_local std::vector<std::uint8_t> encoded;
    cv::imencode(".jpg", bgr, encoded, {cv::IMWRITE_JPEG_QUALITY, quality});
    cv::imdecode(encoded, cv::IMREAD_COLOR, &bgr);
}

SensorNoise::SensorNoise(cv::Size frame, double sigma, std::uint64_t seed)
{
    cv::Mat noise(frame.height + kMargin, frame.width + kMargin, CV_16SC3);
    cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    noise.convertTo(up_, CV_8U);  // saturates: negative values become 0
    const cv::Mat negated = -noise;
    negated.convertTo(down_, CV_8U);
}

void SensorNoise::apply(cv::Mat& bgr, std::uint64_t where) const
{
    if (up_.empty()) return;
    const cv::Rect window(int(where % kMargin), int((where >> 16) % kMargin), bgr.cols, bgr.rows);
    cv::add(bgr, up_(window), bgr);
    cv::subtract(bgr, down_(window), bgr);
}

}  // namespace gc::sim
