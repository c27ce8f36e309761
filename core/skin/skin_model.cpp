#include "skin/skin_model.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

constexpr double kBinWidth = 1.0 / (SkinModel::kBins - 1);

// Membership as a logistic in the Mahalanobis distance, centred on the 3-sigma boundary.
// A width of 0.35 sigma keeps the ramp a few table bins wide for typical skin spreads.
constexpr double kMembershipWidth = 0.35;

void check_bgr(const cv::Mat& bgr, const char* what)
{
    if (bgr.empty()) throw std::invalid_argument(std::string(what) + ": empty image");
    if (bgr.type() != CV_8UC3)
        throw std::invalid_argument(std::string(what) + ": expected CV_8UC3 (BGR), got " +
                                    std::to_string(bgr.channels()) + " channel(s) of depth " +
                                    std::to_string(bgr.depth()));
}

void check_mask(const cv::Mat& bgr, const cv::Mat& mask, const char* what)
{
    if (mask.empty() || mask.type() != CV_8UC1)
        throw std::invalid_argument(std::string(what) + ": mask must be a non-empty CV_8UC1");
    if (mask.size() != bgr.size())
        throw std::invalid_argument(std::string(what) + ": mask size differs from image size");
}

}  // namespace

const std::array<std::uint32_t, 766>& rg_reciprocals()
{
    static const auto table = [] {
        std::array<std::uint32_t, 766> t{};
        for (int s = 1; s < 766; ++s) t[s] = static_cast<std::uint32_t>(std::lround(255.0 * 65536.0 / s));
        return t;
    }();
    return table;
}

SkinModel::SkinModel(const cv::Vec2d& mean, const cv::Matx22d& covariance, int dark_threshold)
    : mean_(mean), cov_(covariance), dark_(dark_threshold)
{
    if (!(mean[0] >= 0.0 && mean[1] >= 0.0 && mean[0] + mean[1] <= 1.0))
        throw std::invalid_argument("SkinModel: mean (r, g) outside the normalised-colour triangle");
    if (dark_threshold < 0 || dark_threshold >= 765)
        throw std::invalid_argument("SkinModel: dark threshold must be in [0, 765)");
    const double det = cov_(0, 0) * cov_(1, 1) - cov_(0, 1) * cov_(1, 0);
    if (!(cov_(0, 0) > 0.0 && cov_(1, 1) > 0.0 && det > 1e-14) || std::abs(cov_(0, 1) - cov_(1, 0)) > 1e-12 ||
        !std::isfinite(det))
        throw std::invalid_argument("SkinModel: covariance is not symmetric positive definite");
    inv_cov_ = cov_.inv();
    norm_ = 1.0 / (2.0 * std::numbers::pi * std::sqrt(det));
    rebuild();
}

const SkinModel& SkinModel::generic()
{
    // Skin tones from pale to dark cluster near r = 0.45, g = 0.31 in normalised colour,
    // spread mostly along r (0.40-0.48 from fair to dark under white light): broad, but
    // with grey (r = g = 1/3) at 3.9 sigma, so that sensor noise on a grey sleeve (a
    // pixel's r moves by about 0.5 sigma at a channel sum of 150) leaves it outside the
    // 3-sigma segmentation. Refined by fit() once the hand is found.
    static const SkinModel prior = [] {
        const double sr = 0.03, sg = 0.02, rho = -0.3;
        return SkinModel({0.45, 0.31}, {sr * sr, rho * sr * sg, rho * sr * sg, sg * sg});
    }();
    return prior;
}

SkinModel SkinModel::fit(const cv::Mat& bgr, const cv::Mat& mask, int dark_threshold, int min_pixels)
{
    check_bgr(bgr, "SkinModel::fit");
    check_mask(bgr, mask, "SkinModel::fit");
    if (dark_threshold < 0 || dark_threshold >= 765)
        throw std::invalid_argument("SkinModel::fit: dark threshold must be in [0, 765)");
    // Accumulate in double: sums over a whole frame of normalised values stay exact enough.
    double n = 0, sr = 0, sg = 0, srr = 0, sgg = 0, srg = 0, si = 0, sii = 0;
    for (int y = 0; y < bgr.rows; ++y) {
        const auto* p = bgr.ptr<cv::Vec3b>(y);
        const auto* m = mask.ptr<std::uint8_t>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            if (!m[x]) continue;
            const int sum = p[x][0] + p[x][1] + p[x][2];
            if (sum < dark_threshold || sum == 0) continue;
            const double r = p[x][2] / double(sum), g = p[x][1] / double(sum);
            n += 1;
            sr += r;
            sg += g;
            srr += r * r;
            sgg += g * g;
            srg += r * g;
            si += sum;
            sii += double(sum) * sum;
        }
    }
    if (n < std::max(min_pixels, 2))
        throw std::invalid_argument("SkinModel::fit: only " + std::to_string(int(n)) +
                                    " usable (masked, non-dark) pixels, need " +
                                    std::to_string(std::max(min_pixels, 2)));
    const double mr = sr / n, mg = sg / n;
    // A floor on the variance: quantisation alone gives (1/255)^2 / 12 per channel, and a
    // perfectly flat synthetic patch must not produce a singular model.
    const double floor_var = 1e-5;
    const double vr = std::max(srr / n - mr * mr, floor_var);
    const double vg = std::max(sgg / n - mg * mg, floor_var);
    double crg = srg / n - mr * mg;
    const double max_c = 0.95 * std::sqrt(vr * vg);
    crg = std::clamp(crg, -max_c, max_c);
    SkinModel model({mr, mg}, {vr, crg, crg, vg}, dark_threshold);
    const double mi = si / n;
    model.set_brightness_band(mi, std::sqrt(std::max(sii / n - mi * mi, 1.0)));
    return model;
}

void SkinModel::set_brightness_band(double mean, double sd)
{
    if (!(mean > 0.0 && mean <= 765.0 && sd > 0.0 && std::isfinite(sd)))
        throw std::invalid_argument("SkinModel: brightness band needs 0 < mean <= 765, sd > 0");
    brightness_mean_ = mean;
    brightness_sd_ = sd;
    if (!tables_)
        rebuild();  // a model moved from: its tables made again from its parameters
    else if (tables_.use_count() > 1)
        tables_ = std::make_shared<Tables>(*tables_);
    rebuild_brightness();
}

void SkinModel::rebuild_brightness()
{
    auto& t = tables_->brightness;
    const double width = std::max(brightness_sd_, kBrightnessFloor * brightness_mean_ / kBrightnessSigma);
    for (int i = 0; i < 766; ++i) {
        if (brightness_sd_ <= 0.0) {
            t[i] = 255;
            continue;
        }
        // The same logistic as the colour membership: 128 at the band's edge.
        const double d = std::abs(i - brightness_mean_) / width * (kBoundarySigma / kBrightnessSigma);
        t[i] =
            static_cast<std::uint8_t>(std::lround(255.0 / (1.0 + std::exp((d - kBoundarySigma) / kMembershipWidth))));
    }
    table_brightness_ = brightness_mean_;
}

double SkinModel::mahalanobis2(double r, double g) const
{
    const double dr = r - mean_[0], dg = g - mean_[1];
    return dr * (inv_cov_(0, 0) * dr + inv_cov_(0, 1) * dg) + dg * (inv_cov_(1, 0) * dr + inv_cov_(1, 1) * dg);
}

double SkinModel::density(double r, double g) const { return norm_ * std::exp(-0.5 * mahalanobis2(r, g)); }

double SkinModel::threshold_density() const { return norm_ * std::exp(-0.5 * kBoundarySigma * kBoundarySigma); }

bool SkinModel::is_skin(const cv::Vec3b& bgr) const
{
    const int sum = bgr[0] + bgr[1] + bgr[2];
    if (sum < dark_ || sum == 0) return false;
    return mahalanobis2(bgr[2] / double(sum), bgr[1] / double(sum)) <= kBoundarySigma * kBoundarySigma;
}

void SkinModel::rebuild()
{
    // Copy-on-write: copies of a model share tables until one of them adapts.
    if (!tables_) {
        tables_ = std::make_shared<Tables>();
        tables_->brightness.fill(255);
    } else if (tables_.use_count() > 1) {
        tables_ = std::make_shared<Tables>(*tables_);
    }
    // Values depend on d^2 only: tabulate that 1-D function once, then fill the 2-D tables
    // with one quadratic form per bin (cheap enough to redo after every mean update).
    constexpr int kD2Steps = 64;     // per unit of d^2
    constexpr double kD2Max = 40.0;  // beyond: every table value is 0
    static const auto profile = [] {
        std::array<std::array<std::uint8_t, 2>, int(kD2Max * kD2Steps) + 1> t{};
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double d2 = double(i) / kD2Steps;
            const double d = std::sqrt(d2);
            t[i][0] = static_cast<std::uint8_t>(std::lround(255.0 * std::exp(-0.5 * d2)));
            t[i][1] = static_cast<std::uint8_t>(
                std::lround(255.0 / (1.0 + std::exp((d - kBoundarySigma) / kMembershipWidth))));
        }
        return t;
    }();
    Tables& t = *tables_;
    for (int ir = 0; ir < kBins; ++ir) {
        const double dr = ir * kBinWidth - mean_[0];
        const double a = inv_cov_(0, 0) * dr * dr;
        const double b = 2.0 * inv_cov_(0, 1) * dr;
        for (int ig = 0; ig < kBins; ++ig) {
            const double dg = ig * kBinWidth - mean_[1];
            const double d2 = a + b * dg + inv_cov_(1, 1) * dg * dg;
            const std::size_t k = std::size_t(ir) * kBins + ig;
            if (d2 >= kD2Max) {
                t.probability[k] = t.membership[k] = t.inside[k] = 0;
                continue;
            }
            const auto& v = profile[std::size_t(d2 * kD2Steps + 0.5)];
            t.probability[k] = v[0];
            t.membership[k] = v[1];
            t.inside[k] = d2 <= kBoundarySigma * kBoundarySigma ? 255 : 0;
        }
    }
    table_mean_ = mean_;
}

namespace {

template <bool WithBand>
void lookup_rows(const cv::Mat& bgr, const cv::Rect& r, const std::uint8_t* lut, const std::uint8_t* band, int dark,
                 cv::Mat1b& out)
{
    const auto& rec = rg_reciprocals();
    for (int y = r.y; y < r.y + r.height; ++y) {
        const auto* p = bgr.ptr<std::uint8_t>(y) + 3 * r.x;
        auto* o = out.ptr<std::uint8_t>(y) + r.x;
        for (int x = 0; x < r.width; ++x, p += 3) {
            const int sum = p[0] + p[1] + p[2];
            if (sum < dark) {
                o[x] = 0;
                continue;
            }
            const std::uint32_t inv = rec[sum];
            const std::uint32_t ir = (p[2] * inv + (1u << 15)) >> 16;
            const std::uint32_t ig = (p[1] * inv + (1u << 15)) >> 16;
            const std::uint8_t v = lut[ir * SkinModel::kBins + ig];
            if constexpr (WithBand)
                o[x] = std::min(v, band[sum]);
            else
                o[x] = v;
        }
    }
}

}  // namespace

void SkinModel::apply(const cv::Mat& bgr, const cv::Rect& roi, const Table& table, cv::Mat1b& out,
                      const std::uint8_t* band) const
{
    const cv::Rect r = roi & cv::Rect(0, 0, bgr.cols, bgr.rows);
    if (out.size() != bgr.size()) out.create(bgr.size());
    const int dark = std::max(dark_, 1);
    if (band)
        lookup_rows<true>(bgr, r, table.data(), band, dark, out);
    else
        lookup_rows<false>(bgr, r, table.data(), nullptr, dark, out);
}

void SkinModel::probability(const cv::Mat& bgr, cv::Mat1b& out) const
{
    check_bgr(bgr, "SkinModel::probability");
    apply(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), tables_->probability, out);
}

void SkinModel::probability(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat1b& out) const
{
    check_bgr(bgr, "SkinModel::probability");
    apply(bgr, roi, tables_->probability, out);
}

void SkinModel::membership(const cv::Mat& bgr, const cv::Rect& roi, cv::Mat1b& out) const
{
    check_bgr(bgr, "SkinModel::membership");
    apply(bgr, roi, tables_->membership, out, has_brightness_band() ? tables_->brightness.data() : nullptr);
}

cv::Mat1b SkinModel::segment(const cv::Mat& bgr) const
{
    cv::Mat1b out;
    segment(bgr, out);
    return out;
}

void SkinModel::segment(const cv::Mat& bgr, cv::Mat1b& out) const
{
    check_bgr(bgr, "SkinModel::segment");
    apply(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), tables_->inside, out);
}

bool SkinModel::update_mean(const cv::Mat& bgr, const cv::Mat& mask, double rate, double gate_sigma, int min_pixels)
{
    check_bgr(bgr, "SkinModel::update_mean");
    check_mask(bgr, mask, "SkinModel::update_mean");
    if (!(rate > 0.0 && rate <= 1.0)) throw std::invalid_argument("SkinModel::update_mean: rate must be in (0, 1]");
    const double gate2 = gate_sigma * gate_sigma;
    // Only the bounding box of the mask is visited: the contour covers a small part.
    const cv::Rect box = cv::boundingRect(mask);
    double n = 0, sr = 0, sg = 0, si = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
        const auto* p = bgr.ptr<cv::Vec3b>(y);
        const auto* m = mask.ptr<std::uint8_t>(y);
        for (int x = box.x; x < box.x + box.width; ++x) {
            if (!m[x]) continue;
            const int sum = p[x][0] + p[x][1] + p[x][2];
            if (sum < dark_ || sum == 0) continue;
            const double r = p[x][2] / double(sum), g = p[x][1] / double(sum);
            if (mahalanobis2(r, g) > gate2) continue;
            n += 1;
            sr += r;
            sg += g;
            si += sum;
        }
    }
    if (n < std::max(min_pixels, 1)) return false;
    mean_ = (1.0 - rate) * mean_ + rate * cv::Vec2d(sr / n, sg / n);
    if (has_brightness_band()) {
        brightness_mean_ = (1.0 - rate) * brightness_mean_ + rate * si / n;
        if (std::abs(brightness_mean_ - table_brightness_) > 0.5) {
            if (tables_.use_count() > 1) tables_ = std::make_shared<Tables>(*tables_);
            rebuild_brightness();
        }
    }
    // Rebuild only once the mean has moved by a visible fraction of a table bin.
    if (std::abs(mean_[0] - table_mean_[0]) + std::abs(mean_[1] - table_mean_[1]) > 0.25 * kBinWidth) rebuild();
    return true;
}

}  // namespace gc
