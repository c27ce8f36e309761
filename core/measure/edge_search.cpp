#include "measure/edge_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gc {

namespace {

// The bilinear blend of four neighbouring values at fractions (fx, fy) from v00.
inline double blend(double v00, double v10, double v01, double v11, double fx, double fy)
{
    const double top = v00 * (1.0 - fx) + v10 * fx;
    const double bottom = v01 * (1.0 - fx) + v11 * fx;
    return top * (1.0 - fy) + bottom * fy;
}

// Bilinear sample of a BGR image, clamped to its border, read through row pointers: this
// runs for every step of every colour edge of every refinement.
cv::Vec3d sample_colour(const cv::Mat& bgr, double x, double y)
{
    x = std::clamp(x, 0.0, bgr.cols - 1.0);
    y = std::clamp(y, 0.0, bgr.rows - 1.0);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, bgr.cols - 1), y1 = std::min(y0 + 1, bgr.rows - 1);
    const double fx = x - x0, fy = y - y0;
    const std::uint8_t* top = bgr.ptr<std::uint8_t>(y0);
    const std::uint8_t* bottom = bgr.ptr<std::uint8_t>(y1);
    cv::Vec3d out;
    for (int c = 0; c < 3; ++c)
        out[c] = blend(top[3 * x0 + c], top[3 * x1 + c], bottom[3 * x0 + c], bottom[3 * x1 + c], fx, fy);
    return out;
}

}  // namespace

double colour_edge_offset(const cv::Mat& bgr, cv::Point2d p, cv::Point2d n, double offset, double reach)
{
    // Below this squared colour distance (about 20 grey levels) inside and outside are too
    // alike for their mixing ratio to be measured through sensor noise.
    constexpr double kMinContrast2 = 400.0;
    constexpr double kStep = 0.25;
    if (bgr.empty() || bgr.type() != CV_8UC3 || !(reach > 0.0)) return offset;
    const auto at = [&](double t) { return sample_colour(bgr, p.x + t * n.x, p.y + t * n.y); };
    const cv::Vec3d inside = at(offset - reach), outside = at(offset + reach);
    const cv::Vec3d span = outside - inside;
    const double contrast2 = span.dot(span);
    if (contrast2 < kMinContrast2) return offset;
    double prev = -1.0;
    for (double t = offset - reach; t <= offset + reach + 1e-9; t += kStep) {
        const double mix = (at(t) - inside).dot(span) / contrast2;  // 0 skin .. 1 background
        if (prev >= 0.0 && prev < 0.5 && mix >= 0.5) return t - kStep + kStep * (0.5 - prev) / (mix - prev);
        prev = std::max(mix, 0.0);
    }
    return offset;
}

double sample_bilinear(const cv::Mat1b& map, double x, double y)
{
    // Inside, where all four pixels exist (most samples), without a bounds test per pixel
    // (and, x and y being non-negative, truncation is the floor).
    if (x >= 0.0 && y >= 0.0 && x < map.cols - 1.0 && y < map.rows - 1.0) {
        const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
        const std::uint8_t* top = map.ptr<std::uint8_t>(y0) + x0;
        const std::uint8_t* bottom = map.ptr<std::uint8_t>(y0 + 1) + x0;
        return blend(top[0], top[1], bottom[0], bottom[1], x - x0, y - y0);
    }
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    auto at = [&](int xx, int yy) -> double {
        if (xx < 0 || yy < 0 || xx >= map.cols || yy >= map.rows) return 0.0;
        return map(yy, xx);
    };
    return blend(at(x0, y0), at(x0 + 1, y0), at(x0, y0 + 1), at(x0 + 1, y0 + 1), x - x0, y - y0);
}

bool find_skin_edge_precise(const cv::Mat1b& map, cv::Point2d p, cv::Point2d n, double half, double step,
                            double& offset)
{
    if (!(step > 0.0) || !(half > 0.0)) return false;
    const int count = static_cast<int>(std::floor(2.0 * half / step));
    double prev = -1.0;
    for (int k = 0; k <= count; ++k) {
        const double t = -half + k * step;
        const double v = sample_bilinear(map, p.x + t * n.x, p.y + t * n.y);
        if (prev >= kSkinEdgeLevel && v < kSkinEdgeLevel) {
            offset = t - step + step * (prev - kSkinEdgeLevel) / (prev - v);
            return true;
        }
        prev = v;
    }
    return false;
}

}  // namespace gc
