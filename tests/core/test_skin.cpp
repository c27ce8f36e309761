#include "skin/skin_model.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>
#include <stdexcept>

namespace {

// Converts a normalised colour and a brightness sum to a BGR pixel.
cv::Vec3b pixel_from_rg(double r, double g, double sum)
{
    const double b = 1.0 - r - g;
    return {cv::saturate_cast<std::uint8_t>(b * sum), cv::saturate_cast<std::uint8_t>(g * sum),
            cv::saturate_cast<std::uint8_t>(r * sum)};
}

// An image whose pixels are drawn from a known normal over (r, g).
cv::Mat3b sample_image(const cv::Vec2d& mean, double sr, double sg, double rho, int n, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> z;
    cv::Mat3b img(n, n);
    for (auto& p : img) {
        const double z1 = z(rng), z2 = z(rng);
        const double r = mean[0] + sr * z1;
        const double g = mean[1] + sg * (rho * z1 + std::sqrt(1 - rho * rho) * z2);
        p = pixel_from_rg(r, g, 480.0);  // bright but unsaturated: small rounding noise
    }
    return img;
}

TEST(SkinModel, FitRecoversKnownMeanAndCovariance)
{
    const cv::Vec2d mean{0.46, 0.31};
    const double sr = 0.02, sg = 0.012, rho = -0.4;
    const cv::Mat3b img = sample_image(mean, sr, sg, rho, 200, 7);
    const cv::Mat1b mask(img.size(), 255);
    const auto model = gc::SkinModel::fit(img, mask);
    EXPECT_NEAR(model.mean()[0], mean[0], 1e-3);
    EXPECT_NEAR(model.mean()[1], mean[1], 1e-3);
    // Integer rounding of the pixels adds a little variance (~(1/480)^2 / 4).
    EXPECT_NEAR(std::sqrt(model.covariance()(0, 0)), sr, 0.1 * sr);
    EXPECT_NEAR(std::sqrt(model.covariance()(1, 1)), sg, 0.1 * sg);
    const double fitted_rho = model.covariance()(0, 1) / std::sqrt(model.covariance()(0, 0) * model.covariance()(1, 1));
    EXPECT_NEAR(fitted_rho, rho, 0.08);
}

TEST(SkinModel, FitIgnoresUnmaskedAndDarkPixels)
{
    cv::Mat3b img(100, 100, pixel_from_rg(0.2, 0.5, 400));  // green background
    cv::Mat1b mask(img.size(), 0);
    cv::rectangle(img, cv::Rect(20, 20, 40, 40), pixel_from_rg(0.5, 0.3, 500), cv::FILLED);
    cv::rectangle(mask, cv::Rect(20, 20, 40, 40), 255, cv::FILLED);
    // Dark pixels inside the mask with a wild normalised colour must not count.
    cv::rectangle(img, cv::Rect(20, 20, 10, 10), cv::Vec3b(0, 0, 20), cv::FILLED);
    const auto model = gc::SkinModel::fit(img, mask);
    EXPECT_NEAR(model.mean()[0], 0.5, 0.01);
    EXPECT_NEAR(model.mean()[1], 0.3, 0.01);
}

TEST(SkinModel, ThresholdIsDensityAtThreeSigma)
{
    const gc::SkinModel m({0.45, 0.3}, {4e-4, 0, 0, 1e-4});
    // 3 sigma along r: r = 0.45 + 3 * 0.02.
    EXPECT_NEAR(m.density(0.51, 0.3), m.threshold_density(), 1e-9 * m.threshold_density());
    EXPECT_NEAR(m.mahalanobis2(0.51, 0.3), 9.0, 1e-9);
    EXPECT_GT(m.density(0.45, 0.3), m.threshold_density());
}

TEST(SkinModel, MapsAgreeWithExactModel)
{
    const gc::SkinModel m({0.45, 0.3}, {4e-4, -1e-4, -1e-4, 2e-4});
    cv::Mat3b img(64, 64);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.12, 0.12);
    for (auto& p : img) p = pixel_from_rg(0.45 + u(rng), 0.3 + u(rng), 500);
    cv::Mat1b prob, seg, memb;
    m.probability(img, prob);
    m.segment(img, seg);
    m.membership(img, cv::Rect(0, 0, 64, 64), memb);
    int disagreements = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const cv::Vec3b p = img(y, x);
            const double s = p[0] + p[1] + p[2];
            const double d2 = m.mahalanobis2(p[2] / s, p[1] / s);
            // Table quantisation (1/255 in r and g) only matters right at the boundary.
            if (std::abs(std::sqrt(d2) - 3.0) > 0.4) disagreements += (seg(y, x) == 255) != (d2 <= 9.0);
            EXPECT_NEAR(prob(y, x), 255.0 * std::exp(-0.5 * d2), 40.0);
            if (d2 < 4.0) {
                EXPECT_GT(memb(y, x), 200);
            }
            if (d2 > 25.0) {
                EXPECT_LT(memb(y, x), 10);
            }
        }
    EXPECT_EQ(disagreements, 0);
}

TEST(SkinModel, RoiMapWritesOnlyTheRoi)
{
    const auto m = gc::SkinModel::generic();
    cv::Mat3b img(50, 60, pixel_from_rg(0.45, 0.31, 450));
    cv::Mat1b out(img.size(), 7);
    m.probability(img, cv::Rect(10, 10, 20, 20), out);
    EXPECT_EQ(out(5, 5), 7);
    EXPECT_GT(out(15, 15), 250);  // at the mean, up to the pixel's rounding
    // An ROI partly outside the frame is clipped, not an error.
    m.membership(img, cv::Rect(50, 40, 100, 100), out);
    EXPECT_GT(out(45, 55), 200);
}

TEST(SkinModel, DarkPixelsAreNeverSkin)
{
    const auto m = gc::SkinModel::generic();
    const cv::Mat3b img(8, 8, pixel_from_rg(0.45, 0.31, 40));
    EXPECT_EQ(cv::countNonZero(m.segment(img)), 0);
    EXPECT_FALSE(m.is_skin(img(0, 0)));
}

TEST(SkinModel, UpdateMeanFollowsLightingAndGatesOutliers)
{
    gc::SkinModel m({0.45, 0.30}, {4e-4, 0, 0, 2e-4});
    cv::Mat3b img(40, 40, pixel_from_rg(0.47, 0.30, 500));
    // A quarter of the masked area is background far from skin: gated out.
    cv::rectangle(img, cv::Rect(0, 0, 20, 20), pixel_from_rg(0.2, 0.5, 500), cv::FILLED);
    const cv::Mat1b mask(img.size(), 255);
    for (int i = 0; i < 60; ++i) ASSERT_TRUE(m.update_mean(img, mask, 0.2));
    EXPECT_NEAR(m.mean()[0], 0.47, 2e-3);
    EXPECT_NEAR(m.mean()[1], 0.30, 2e-3);
    // The tables follow the adapted mean.
    cv::Mat1b prob;
    m.probability(img, prob);
    EXPECT_GT(prob(30, 30), 240);
    // Nothing usable under the mask: no change.
    const cv::Mat1b empty(img.size(), 0);
    EXPECT_FALSE(m.update_mean(img, empty, 0.2));
}

TEST(SkinModel, BrightnessBandSeparatesSameToneSkin)
{
    // The hand and a brighter object of exactly the same normalised colour.
    cv::Mat3b img(40, 80, pixel_from_rg(0.47, 0.31, 300));
    cv::rectangle(img, cv::Rect(40, 0, 40, 40), pixel_from_rg(0.47, 0.31, 520), cv::FILLED);
    cv::Mat1b hand(img.size(), uchar(0));
    cv::rectangle(hand, cv::Rect(0, 0, 40, 40), 255, cv::FILLED);
    const auto m = gc::SkinModel::fit(img, hand);
    ASSERT_TRUE(m.has_brightness_band());
    EXPECT_NEAR(m.brightness_mean(), 300.0, 3.0);
    cv::Mat1b memb, seg;
    m.membership(img, cv::Rect(0, 0, img.cols, img.rows), memb);
    EXPECT_GT(memb(20, 10), 200);
    EXPECT_LT(memb(20, 60), 20);
    // The segmentation (the thesis's 3-sigma colour test) ignores brightness.
    m.segment(img, seg);
    EXPECT_EQ(seg(20, 60), 255);
    // A model from parameters has no band until one is set.
    gc::SkinModel p({0.47, 0.31}, {4e-4, 0, 0, 2e-4});
    EXPECT_FALSE(p.has_brightness_band());
    p.membership(img, cv::Rect(0, 0, img.cols, img.rows), memb);
    EXPECT_GT(memb(20, 60), 200);
    p.set_brightness_band(300.0, 10.0);
    p.membership(img, cv::Rect(0, 0, img.cols, img.rows), memb);
    EXPECT_LT(memb(20, 60), 20);
    EXPECT_THROW(p.set_brightness_band(300.0, 0.0), std::invalid_argument);
}

TEST(SkinModel, CopiesAreIndependent)
{
    gc::SkinModel a({0.45, 0.30}, {4e-4, 0, 0, 2e-4});
    const gc::SkinModel b = a;
    const cv::Mat3b img(10, 10, pixel_from_rg(0.5, 0.30, 500));
    ASSERT_TRUE(a.update_mean(img, cv::Mat1b(img.size(), 255), 1.0));
    cv::Mat1b pa, pb;
    a.probability(img, pa);
    b.probability(img, pb);
    EXPECT_GT(pa(0, 0), pb(0, 0));
}

// A model moved from takes a brightness band as a fresh model with its parameters does (its
// tables were gone, and setting the band read through a null pointer).
TEST(SkinModel, AModelMovedFromTakesABrightnessBand)
{
    gc::SkinModel a({0.45, 0.30}, {4e-4, 0, 0, 2e-4});
    const gc::SkinModel taken = std::move(a);
    a.set_brightness_band(300.0, 10.0);
    gc::SkinModel fresh({0.45, 0.30}, {4e-4, 0, 0, 2e-4});
    fresh.set_brightness_band(300.0, 10.0);
    const cv::Mat3b img(10, 10, pixel_from_rg(0.45, 0.30, 300));
    cv::Mat1b ma, mf;
    a.probability(img, ma);
    fresh.probability(img, mf);
    EXPECT_EQ(cv::norm(ma, mf, cv::NORM_INF), 0.0);
    EXPECT_GT(mf(0, 0), 200);
    EXPECT_EQ(taken.has_brightness_band(), false);
}

TEST(SkinModel, BadInputsThrowClearErrors)
{
    const auto m = gc::SkinModel::generic();
    cv::Mat1b out;
    EXPECT_THROW(m.probability(cv::Mat(), out), std::invalid_argument);
    EXPECT_THROW(m.segment(cv::Mat1b(10, 10)), std::invalid_argument);
    EXPECT_THROW(m.segment(cv::Mat(10, 10, CV_8UC4)), std::invalid_argument);
    const cv::Mat3b img(10, 10, cv::Vec3b(50, 80, 200));
    EXPECT_THROW(gc::SkinModel::fit(img, cv::Mat1b(5, 5, 255)), std::invalid_argument);
    EXPECT_THROW(gc::SkinModel::fit(img, cv::Mat1b(10, 10, uchar(0))), std::invalid_argument);
    EXPECT_THROW(gc::SkinModel({0.4, 0.3}, {1e-4, 0, 0, -1e-4}), std::invalid_argument);
    EXPECT_THROW(gc::SkinModel({0.8, 0.3}, {1e-4, 0, 0, 1e-4}), std::invalid_argument);
    try {
        gc::SkinModel::fit(img, cv::Mat1b(10, 10, uchar(0)));
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("pixels"), std::string::npos);
    }
}

}  // namespace

TEST(SkinModel, GenericModelTakesSkinTonesButNotNoisyGrey)
{
    const auto m = gc::SkinModel::generic();
    cv::RNG rng(7);
    // Skin from fair to dark under white light, at several brightnesses.
    for (double r = 0.40; r <= 0.4801; r += 0.02)
        for (double g : {0.31, 0.32})
            for (int sum : {200, 400, 600}) EXPECT_TRUE(m.is_skin(pixel_from_rg(r, g, sum))) << r << " " << g;
    // Grey with sensor noise (sd 2.5 levels per channel): a dark sleeve, a wall. Dark, the
    // noise moves its chromaticity most; a model with grey inside 3 sigma takes much of it.
    for (int sum : {120, 150, 300, 600}) {
        cv::Mat3b grey(100, 100, cv::Vec3b::all(cv::saturate_cast<uchar>(sum / 3)));
        cv::Mat3s noise(grey.size());
        rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.5);
        cv::Mat3s sum16;
        grey.convertTo(sum16, CV_16SC3);
        sum16 += noise;
        sum16.convertTo(grey, CV_8UC3);
        EXPECT_LT(cv::countNonZero(m.segment(grey)), (sum < 300 ? 0.1 : 0.001) * grey.total()) << sum;
    }
}
