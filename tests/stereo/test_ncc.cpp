// Correspondence by normalised cross-correlation along a segment.
#include "stereo/epipolar_ncc.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace {

cv::Mat textured(cv::Size size, int seed)
{
    cv::Mat noise(size, CV_32F);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
    cv::normalize(noise, noise, 20, 235, cv::NORM_MINMAX);
    cv::Mat out;
    noise.convertTo(out, CV_8U);
    return out;
}

// `right` shows `left` moved by -disparity along x (sub-pixel, bilinear).
cv::Mat shifted(const cv::Mat& left, double disparity)
{
    cv::Mat right;
    const cv::Matx23d shift(1, 0, -disparity, 0, 1, 0);
    cv::warpAffine(left, right, shift, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
    return right;
}

gc::NccView view_of(const cv::Mat& grey, cv::Point offset)
{
    gc::NccView v;
    v.prepare(grey, offset, 4);
    v.mask = cv::Mat1b(grey.size(), 255);
    return v;
}

TEST(EpipolarNcc, FindsTheSubPixelShift)
{
    const cv::Mat left = textured({200, 120}, 5);
    for (double disparity : {12.0, 23.25, 31.5, 40.8}) {
        const cv::Mat right = shifted(left, disparity);
        // Regions of a larger image: offsets must be honoured.
        const gc::NccView lv = view_of(left, {100, 50}), rv = view_of(right, {100, 50});
        gc::EpipolarNcc ncc(4, 0.7, 3.0);
        double worst = 0.0;
        int found = 0;
        for (int y = 20; y < 100; y += 9)
            for (int x = 80; x < 180; x += 11) {
                const cv::Point p(100 + x, 50 + y);
                if (!ncc.set_template(lv, p)) continue;
                const gc::NccMatch m = ncc.search(rv, {p.x - 2.0, double(p.y)}, {p.x - 60.0, double(p.y)});
                ASSERT_TRUE(m.found);
                ++found;
                worst = std::max(worst, std::abs(m.position.x - (p.x - disparity)));
                EXPECT_DOUBLE_EQ(m.position.y, p.y);
                EXPECT_GT(m.score, 0.9);
            }
        EXPECT_GT(found, 50);
        EXPECT_LT(worst, 0.25) << "disparity " << disparity;
    }
}

TEST(EpipolarNcc, RespectsTheMaskAndRejectsFlatWindows)
{
    const cv::Mat left = textured({160, 80}, 9);
    const cv::Mat right = shifted(left, 20.0);
    gc::NccView lv = view_of(left, {0, 0}), rv = view_of(right, {0, 0});
    gc::EpipolarNcc ncc(4, 0.7, 3.0);
    const cv::Point p(100, 40);
    ASSERT_TRUE(ncc.set_template(lv, p));
    // The true match (x = 80) is masked out: whatever is found lies elsewhere and is weak.
    rv.mask(cv::Rect(70, 0, 20, 80)).setTo(0);
    const gc::NccMatch m = ncc.search(rv, {98.0, 40.0}, {40.0, 40.0});
    EXPECT_TRUE(!m.found || std::abs(m.position.x - 80.0) > 9.0);

    const cv::Mat flat(80, 160, CV_8U, cv::Scalar(128));
    const gc::NccView fv = view_of(flat, {0, 0});
    EXPECT_FALSE(ncc.set_template(fv, p));
    // A template near the border has no full window.
    EXPECT_FALSE(ncc.set_template(lv, {2, 40}));
}

}  // namespace
