// Accuracy measures: the thesis's SNR over a sequence (docs/sim.md), mask IoU, centre error.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace gc {

// Fills a closed contour polygon into a CV_8U mask (255 inside) of the given size.
cv::Mat1b contour_mask(const std::vector<cv::Point2f>& contour, cv::Size size);

double mask_iou(const cv::Mat1b& a, const cv::Mat1b& b);  // 1 when both are empty

// Accumulates signal = 2 * sum I_ref^2 and noise = sum (I_ref - I_track)^2 over frames
// (masks as 0/1), SNR_dB = 10 log10(signal / noise).
class SnrAccumulator {
public:
    void add(const cv::Mat1b& reference, const cv::Mat1b& tracked);
    double snr_db() const;  // +inf when noise is 0, NaN when nothing was added
    std::uint64_t signal() const { return signal_; }
    std::uint64_t noise() const { return noise_; }

private:
    std::uint64_t signal_ = 0;
    std::uint64_t noise_ = 0;
};

// Distance in pixels between the centroids of two masks (NaN if either is empty).
double centre_error_px(const cv::Mat1b& reference, const cv::Mat1b& tracked);

}  // namespace gc
