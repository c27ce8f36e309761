// Correspondence by normalised cross-correlation along an epipolar segment, restricted to
// a region (the other view's hand). Window statistics are precomputed once per frame, so
// a candidate costs one dot product of the zero-mean template with the image window.
#pragma once

#include <opencv2/core.hpp>

namespace gc {

// One view's search data over a region of interest of the (undistorted) image.
struct NccView {
    cv::Point offset;  // of the region in full-image pixels
    cv::Mat1f grey;    // intensities of the region
    cv::Mat1f sigma;   // standard deviation of the window centred on each pixel
    cv::Mat1b mask;    // 255 where a window centre may match (inside the hand)

    // Recomputes grey/sigma for a window of (2 radius + 1)^2 pixels from `grey8` (CV_8U,
    // the region already cut out); reuses the buffers.
    void prepare(const cv::Mat& grey8, cv::Point region_offset, int radius);
};

struct NccMatch {
    bool found = false;
    cv::Point2d position;  // sub-pixel, full-image pixels, on the segment
    cv::Point pixel;       // the integer window centre of the peak, full-image pixels
    double score = -1.0;
};

class EpipolarNcc {
public:
    // radius: window half-size in pixels; min_score: the weakest accepted peak;
    // min_sigma: windows flatter than this (grey levels) carry no signal and are skipped.
    EpipolarNcc(int radius, double min_score, double min_sigma);

    // Loads the zero-mean, unit-norm template of `from` centred on `centre` (full-image
    // pixels). False when the window leaves the region or is too flat.
    bool set_template(const NccView& from, cv::Point centre);

    // The best match of the current template in `to` along the straight segment a -> b
    // (full-image pixels), stepping one pixel along its dominant axis; only centres inside
    // to.mask count. Sub-pixel by a parabola through the peak and its two neighbours.
    NccMatch search(const NccView& to, cv::Point2d a, cv::Point2d b) const;

private:
    double score_at(const NccView& to, int x, int y) const;  // region pixels

    int radius_;
    int side_;
    double min_score_;
    double min_sigma_;
    cv::Mat1f template_;  // side x side, zero mean, divided by (n * sigma)
};

}  // namespace gc
