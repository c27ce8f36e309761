// Skin colour as a bivariate normal over normalised colour (r, g) = (R, G) / (R + G + B),
// with dark pixels rejected (normalised colour is noise there). Per-pixel maps come from
// 256 x 256 tables over quantised (r, g): no division and no exp() per pixel.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <memory>

namespace gc {

class SkinModel {
public:
    // Pixels with R + G + B below this are never skin.
    static constexpr int kDefaultDarkThreshold = 60;
    // Segmentation boundary: Mahalanobis distance 3 (the thesis's 3-sigma threshold).
    static constexpr double kBoundarySigma = 3.0;

    // A model from its parameters. Throws std::invalid_argument unless `covariance` is
    // symmetric positive definite, the mean lies in the rg triangle and 0 <= dark < 765.
    SkinModel(const cv::Vec2d& mean, const cv::Matx22d& covariance, int dark_threshold = kDefaultDarkThreshold);

    // A broad prior of human skin under indoor light, used before any hand was seen. Built
    // once: its lookup table is most of a small detection's cost.
    static const SkinModel& generic();

    // Fits mean and covariance to the non-dark pixels of `bgr` (CV_8UC3) where `mask` is
    // non-zero. Throws std::invalid_argument on a wrong type or size, or fewer than
    // `min_pixels` usable pixels, or degenerate (zero-variance) colours.
    static SkinModel fit(const cv::Mat& bgr, const cv::Mat& mask, int dark_threshold = kDefaultDarkThreshold,
                         int min_pixels = 20);

    // The brightness band (R + G + B) of the fitted pixels: normalised colour cannot tell
    // the hand from a face or an object of the same skin tone, brightness often can.
    // A model built from parameters has none until set_brightness_band().
    bool has_brightness_band() const { return brightness_sd_ > 0.0; }
    double brightness_mean() const { return brightness_mean_; }
    double brightness_sd() const { return brightness_sd_; }
    // Throws std::invalid_argument unless 0 < mean <= 765 and sd > 0.
    void set_brightness_band(double mean, double sd);

    const cv::Vec2d& mean() const { return mean_; }
    const cv::Matx22d& covariance() const { return cov_; }
    int dark_threshold() const { return dark_; }

    double mahalanobis2(double r, double g) const;
    double density(double r, double g) const;  // the normal pdf N(m, Sigma)
    double threshold_density() const;          // the pdf at the 3-sigma boundary
    bool is_skin(const cv::Vec3b& bgr) const;  // exact test, not table-quantised

    // Skin probability map: density / peak density in 0..255 (255 at the mean), 0 for dark
    // pixels. `out` is (re)allocated to the frame size. The ROI overload writes only `roi`
    // (clipped to the frame) of a frame-sized `out` and leaves the rest untouched.
    void probability(const cv::Mat& bgr, cv::Mat1b& out) const;
    void probability(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat1b& out) const;

    // Soft membership for edge localisation: a smooth decreasing function of the
    // Mahalanobis distance d, 255 at the mean, 128 exactly at d = 3 (the segmentation
    // boundary), near 0 beyond d = 4.5. Sub-pixel edges are the 128 crossings. With a
    // brightness band, the result is the smaller of that and the same function of the
    // brightness deviation (in band widths, kBrightnessSigma per band).
    void membership(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat1b& out) const;

    // Binary segmentation, 255 where the pixel is inside the 3-sigma ellipse.
    cv::Mat1b segment(const cv::Mat& bgr) const;
    void segment(const cv::Mat& bgr, cv::Mat1b& out) const;

    // Adaptation to lighting: moves the mean (and the brightness band's mean) by `rate`
    // (0..1] towards the mean colour of the non-dark pixels under `mask` that lie within
    // `gate_sigma` of the current model (so background inside a slightly wrong contour does
    // not drag it). Returns false and changes nothing when fewer than `min_pixels` qualify.
    bool update_mean(const cv::Mat& bgr, const cv::Mat& mask, double rate = 0.1, double gate_sigma = 4.0,
                     int min_pixels = 20);

    static constexpr int kBins = 256;  // table resolution per normalised channel
    // The band's half width in brightness standard deviations, and its floor as a fraction
    // of the mean brightness (shading across a hand is never narrower than that).
    static constexpr double kBrightnessSigma = 3.5;
    static constexpr double kBrightnessFloor = 0.08;

private:
    using Table = std::array<std::uint8_t, kBins * kBins>;
    struct Tables {
        Table probability;
        Table membership;
        Table inside;
        std::array<std::uint8_t, 766> brightness;  // membership by R + G + B
    };
    void rebuild_brightness();
    void rebuild();
    // Looks every pixel of roi up in table; with a brightness band, the result is capped by
    // band[R + G + B] (the band separates same-chromaticity surfaces of other brightness).
    void apply(const cv::Mat& bgr, const cv::Rect& roi, const Table& table, cv::Mat1b& out,
               const std::uint8_t* band = nullptr) const;

    cv::Vec2d mean_;
    cv::Matx22d cov_;
    cv::Matx22d inv_cov_;
    double norm_ = 0.0;  // 1 / (2 pi sqrt(det Sigma))
    int dark_ = kDefaultDarkThreshold;
    double brightness_mean_ = 0.0;
    double brightness_sd_ = 0.0;  // 0: no band
    double table_brightness_ = -1.0;
    cv::Vec2d table_mean_{-1.0, -1.0};  // the mean the tables were last built for
    std::shared_ptr<Tables> tables_;    // shared between copies until one adapts
};

// 16.16 fixed-point reciprocals 255 / (R + G + B): the quantised normalised colour of a
// pixel is then (R * rec[sum]) >> 16, with no division per pixel.
const std::array<std::uint32_t, 766>& rg_reciprocals();

}  // namespace gc
