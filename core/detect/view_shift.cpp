#include "detect/view_shift.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace gc {

namespace {

// The small copy's width: 80 columns keep a 640-pixel frame's shift to 8 pixels, which
// the tracker's own search covers, at about a tenth of a millisecond per frame.
constexpr int kSmallWidth = 80;
// A peak of the normalised cross-power this high is one motion shared by most of the
// frame; a moving hand alone, or noise, stays well below it.
constexpr double kMinPeak = 0.12;
// Shifts below this many small pixels are the hand's or the noise's, not the view's.
constexpr double kMinShift = 1.5;
// Mean grey change (levels) above which the view changed even without a clear shift.
constexpr double kCutChange = 25.0;

}  // namespace

void ViewShift::reset() { has_previous_ = false; }

bool ViewShift::prepare(const cv::Mat& bgr)
{
    const int rows = std::max(8, cvRound(double(bgr.rows) * kSmallWidth / bgr.cols));
    const cv::Size size(kSmallWidth, rows);
    const bool fresh = window_.size() != size || !has_previous_;
    if (window_.size() != size) cv::createHanningWindow(window_, size, CV_32F);
    scale_ = double(bgr.cols) / kSmallWidth;
    // Bilinear to twice the small size, then area: nearly the area average's smoothing at a
    // fifth of its cost on a full frame.
    cv::resize(bgr, half_bgr_, size * 2, 0.0, 0.0, cv::INTER_LINEAR);
    cv::resize(half_bgr_, small_bgr_, size, 0.0, 0.0, cv::INTER_AREA);
    cv::cvtColor(small_bgr_, small_grey_, cv::COLOR_BGR2GRAY);
    std::swap(level_, previous_level_);
    small_grey_.convertTo(level_, CV_32F);
    // The mean is taken out before windowing, so that a change of brightness is no shift.
    const double mean = cv::mean(level_)[0];
    cv::subtract(level_, cv::Scalar(mean), plane_);
    cv::multiply(plane_, window_, plane_);
    std::swap(spectrum_, previous_spectrum_);
    cv::dft(plane_, spectrum_, cv::DFT_COMPLEX_OUTPUT);
    has_previous_ = true;
    return !fresh;
}

ViewChange ViewShift::update(const cv::Mat& bgr)
{
    ViewChange change;
    if (!prepare(bgr)) return change;
    // Cross-power spectrum, normalised to unit magnitude: its inverse peaks at the shift.
    cv::mulSpectrums(spectrum_, previous_spectrum_, cross_, 0, true);
    for (int y = 0; y < cross_.rows; ++y) {
        cv::Vec2f* c = cross_.ptr<cv::Vec2f>(y);
        for (int x = 0; x < cross_.cols; ++x) {
            const float m = std::sqrt(c[x][0] * c[x][0] + c[x][1] * c[x][1]);
            c[x] = m > 1e-6f ? c[x] / m : cv::Vec2f(0.0f, 0.0f);
        }
    }
    cv::idft(cross_, correlation_, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    double peak = 0.0;
    cv::Point at;
    cv::minMaxLoc(correlation_, nullptr, &peak, nullptr, &at);
    // Shifts past half the size wrap round to negative ones.
    const int w = correlation_.cols, h = correlation_.rows;
    const double sx = at.x > w / 2 ? at.x - w : at.x, sy = at.y > h / 2 ? at.y - h : at.y;
    if (peak >= kMinPeak) {
        change.shifted = std::hypot(sx, sy) >= kMinShift;
        change.dx = sx * scale_;
        change.dy = sy * scale_;
    } else {
        change.cut = cv::norm(level_, previous_level_, cv::NORM_L1) / double(level_.total()) > kCutChange;
    }
    return change;
}

}  // namespace gc
