#include "metrics/metrics.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

// Vertices beyond this many pixels from the origin are clamped: a diverged hypothesis must
// not overflow the fixed-point polygon filler, and such a vertex is far outside any frame.
constexpr double kMaxCoordinate = 1.0e6;
// Sub-pixel precision of the polygon filler (fractional bits).
constexpr int kShift = 4;

std::string size_text(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void require_same_size(const cv::Mat1b& a, const cv::Mat1b& b, const char* what)
{
    if (a.empty() || b.empty()) throw std::invalid_argument(std::string(what) + ": empty mask");
    if (a.size() != b.size())
        throw std::invalid_argument(std::string(what) + ": mask sizes differ (" + size_text(a.size()) + " vs " +
                                    size_text(b.size()) + ")");
}

struct PairCounts {
    std::uint64_t a = 0;
    std::uint64_t b = 0;
    std::uint64_t both = 0;
};

// One pass over two equally sized masks; non-zero is "inside".
PairCounts count_pairs(const cv::Mat1b& a, const cv::Mat1b& b)
{
    PairCounts c;
    for (int y = 0; y < a.rows; ++y) {
        const std::uint8_t* pa = a.ptr<std::uint8_t>(y);
        const std::uint8_t* pb = b.ptr<std::uint8_t>(y);
        std::uint64_t na = 0, nb = 0, nboth = 0;
        for (int x = 0; x < a.cols; ++x) {
            const bool ia = pa[x] != 0;
            const bool ib = pb[x] != 0;
            na += ia;
            nb += ib;
            nboth += ia && ib;
        }
        c.a += na;
        c.b += nb;
        c.both += nboth;
    }
    return c;
}

}  // namespace

cv::Mat1b contour_mask(const std::vector<cv::Point2f>& contour, cv::Size size)
{
    if (size.width <= 0 || size.height <= 0)
        throw std::invalid_argument("contour_mask: invalid mask size " + size_text(size));
    cv::Mat1b mask(size, std::uint8_t{0});
    if (contour.size() < 3) return mask;

    std::vector<cv::Point> fixed;
    fixed.reserve(contour.size());
    const double scale = double(1 << kShift);
    for (const cv::Point2f& p : contour) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw std::invalid_argument("contour_mask: contour has a non-finite point");
        const double x = std::clamp(double(p.x), -kMaxCoordinate, kMaxCoordinate);
        const double y = std::clamp(double(p.y), -kMaxCoordinate, kMaxCoordinate);
        fixed.emplace_back(cvRound(x * scale), cvRound(y * scale));
    }
    cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{fixed}, cv::Scalar(255), cv::LINE_8, kShift);
    return mask;
}

double mask_iou(const cv::Mat1b& a, const cv::Mat1b& b)
{
    require_same_size(a, b, "mask_iou");
    const PairCounts c = count_pairs(a, b);
    const std::uint64_t uni = c.a + c.b - c.both;
    if (uni == 0) return 1.0;
    return double(c.both) / double(uni);
}

void SnrAccumulator::add(const cv::Mat1b& reference, const cv::Mat1b& tracked)
{
    require_same_size(reference, tracked, "SnrAccumulator::add");
    const PairCounts c = count_pairs(reference, tracked);
    signal_ += 2 * c.a;
    // With 0/1 masks (I_ref - I_track)^2 is 1 exactly where they disagree.
    noise_ += c.a + c.b - 2 * c.both;
}

double SnrAccumulator::snr_db() const
{
    if (signal_ == 0 && noise_ == 0) return std::numeric_limits<double>::quiet_NaN();
    if (noise_ == 0) return std::numeric_limits<double>::infinity();
    if (signal_ == 0) return -std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(double(signal_) / double(noise_));
}

double centre_error_px(const cv::Mat1b& reference, const cv::Mat1b& tracked)
{
    require_same_size(reference, tracked, "centre_error_px");
    const cv::Moments mr = cv::moments(reference, true);
    const cv::Moments mt = cv::moments(tracked, true);
    if (mr.m00 <= 0.0 || mt.m00 <= 0.0) return std::numeric_limits<double>::quiet_NaN();
    const double dx = mr.m10 / mr.m00 - mt.m10 / mt.m00;
    const double dy = mr.m01 / mr.m00 - mt.m01 / mt.m00;
    return std::hypot(dx, dy);
}

}  // namespace gc
