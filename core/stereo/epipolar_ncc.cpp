#include "stereo/epipolar_ncc.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace gc {

void NccView::prepare(const cv::Mat& grey8, cv::Point region_offset, int radius)
{
    offset = region_offset;
    grey8.convertTo(grey, CV_32F);
    const cv::Size window(2 * radius + 1, 2 * radius + 1);
    cv::Mat1f mean, mean_sq;
    cv::boxFilter(grey, mean, CV_32F, window, cv::Point(-1, -1), true, cv::BORDER_REFLECT);
    cv::sqrBoxFilter(grey, mean_sq, CV_32F, window, cv::Point(-1, -1), true, cv::BORDER_REFLECT);
    sigma.create(grey.size());
    for (int y = 0; y < grey.rows; ++y) {
        const float* m = mean.ptr<float>(y);
        const float* m2 = mean_sq.ptr<float>(y);
        float* s = sigma.ptr<float>(y);
        for (int x = 0; x < grey.cols; ++x) s[x] = std::sqrt(std::max(0.0f, m2[x] - m[x] * m[x]));
    }
}

EpipolarNcc::EpipolarNcc(int radius, double min_score, double min_sigma)
    : radius_(radius), side_(2 * radius + 1), min_score_(min_score), min_sigma_(min_sigma),
      template_(side_, side_, 0.0f)
{
}

bool EpipolarNcc::set_template(const NccView& from, cv::Point centre)
{
    const int x = centre.x - from.offset.x, y = centre.y - from.offset.y;
    if (x < radius_ || y < radius_ || x >= from.grey.cols - radius_ || y >= from.grey.rows - radius_) return false;
    const float s = from.sigma(y, x);
    if (s < min_sigma_) return false;
    const cv::Mat1f window = from.grey(cv::Rect(x - radius_, y - radius_, side_, side_));
    const float mean = static_cast<float>(cv::mean(window)[0]);
    // Dividing by n * sigma_template here leaves one division by sigma_window per candidate.
    const float norm = 1.0f / (static_cast<float>(side_ * side_) * s);
    for (int r = 0; r < side_; ++r) {
        const float* src = window.ptr<float>(r);
        float* dst = template_.ptr<float>(r);
        for (int c = 0; c < side_; ++c) dst[c] = (src[c] - mean) * norm;
    }
    return true;
}

double EpipolarNcc::score_at(const NccView& to, int x, int y) const
{
    // The template has zero mean, so the window's mean drops out of the covariance.
    float acc = 0.0f;
    for (int r = 0; r < side_; ++r) {
        const float* t = template_.ptr<float>(r);
        const float* w = to.grey.ptr<float>(y - radius_ + r) + (x - radius_);
        for (int c = 0; c < side_; ++c) acc += t[c] * w[c];
    }
    return acc / to.sigma(y, x);
}

NccMatch EpipolarNcc::search(const NccView& to, cv::Point2d a, cv::Point2d b) const
{
    NccMatch best;
    const cv::Point2d d = b - a;
    const double length = std::max(std::abs(d.x), std::abs(d.y));
    if (!(length >= 1.0) || !std::isfinite(length)) return best;
    const int steps = static_cast<int>(std::ceil(length));
    const cv::Point2d step = d * (1.0 / steps);

    // Clip the walk to the region so the loop only visits useful positions.
    const cv::Rect inner(to.offset.x + radius_, to.offset.y + radius_, to.grey.cols - 2 * radius_,
                         to.grey.rows - 2 * radius_);
    if (inner.width <= 0 || inner.height <= 0) return best;

    // Only the steps whose rounded centre can fall inside the region (half a pixel of slack).
    double k_lo = 0.0, k_hi = steps;
    const auto clip = [&](double start, double delta, double lo, double hi) {
        if (std::abs(delta) < 1e-12) {
            if (start < lo - 0.5 || start > hi + 0.5) k_hi = -1.0;
            return;
        }
        double t0 = (lo - 0.5 - start) / delta, t1 = (hi + 0.5 - start) / delta;
        if (t0 > t1) std::swap(t0, t1);
        k_lo = std::max(k_lo, t0);
        k_hi = std::min(k_hi, t1);
    };
    clip(a.x, step.x, inner.x, inner.x + inner.width - 1);
    clip(a.y, step.y, inner.y, inner.y + inner.height - 1);
    if (k_hi < k_lo) return best;

    const int first = std::max(0, static_cast<int>(std::floor(k_lo)));
    const int last = std::min(steps, static_cast<int>(std::ceil(k_hi)));
    // Score of step k; -2 where no window may be placed.
    const auto score_k = [&](int k) {
        if (k < first || k > last) return -2.0;
        const cv::Point2d p = a + step * static_cast<double>(k);
        const int x = cvRound(p.x) - to.offset.x, y = cvRound(p.y) - to.offset.y;
        if (x < radius_ || y < radius_ || x >= to.grey.cols - radius_ || y >= to.grey.rows - radius_) return -2.0;
        if (!to.mask(y, x) || to.sigma(y, x) < min_sigma_) return -2.0;
        return score_at(to, x, y);
    };

    // Coarse pass every other step (the correlation peak of a window this wide spans
    // several pixels), then the neighbours of the coarse peak.
    int best_k = -1;
    for (int k = first; k <= last; k += 2) {
        const double sc = score_k(k);
        if (sc > best.score) best.score = sc, best_k = k;
    }
    if (best_k < 0) return best;
    double before = score_k(best_k - 1), after = score_k(best_k + 1);
    while (before > best.score || after > best.score) {
        if (before > after) {
            after = best.score;
            best.score = before;
            --best_k;
            before = score_k(best_k - 1);
        } else {
            before = best.score;
            best.score = after;
            ++best_k;
            after = score_k(best_k + 1);
        }
    }
    if (best.score < min_score_) return best;
    const cv::Point2d peak = a + step * static_cast<double>(best_k);
    best.pixel = {cvRound(peak.x), cvRound(peak.y)};

    double offset = 0.0;
    if (before > -2.0 && after > -2.0) {
        const double denom = before - 2.0 * best.score + after;
        if (denom < 0.0) offset = std::clamp(0.5 * (before - after) / denom, -0.5, 0.5);
    }
    best.position = a + step * (best_k + offset);
    best.found = true;
    return best;
}

}  // namespace gc
