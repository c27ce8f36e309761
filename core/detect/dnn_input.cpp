#include "detect/dnn_input.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace gc {

cv::Mat make_square_blob(int side)
{
    const int shape[] = {1, 3, side, side};
    return cv::Mat(4, shape, CV_32F);
}

void fill_rgb_blob(const cv::Mat3b& bgr, double scale, double shift, cv::Mat3f& scratch, cv::Mat& blob)
{
    const int side = bgr.rows;
    if (bgr.cols != side || blob.dims != 4 || blob.size[2] != side || blob.size[3] != side)
        throw std::logic_error("fill_rgb_blob: the image and the blob differ in size");
    bgr.convertTo(scratch, CV_32F, scale, shift);
    float* data = blob.ptr<float>();
    const int plane = side * side;
    cv::Mat planes[] = {cv::Mat(side, side, CV_32F, data), cv::Mat(side, side, CV_32F, data + plane),
                        cv::Mat(side, side, CV_32F, data + 2 * plane)};
    const int bgr_to_rgb[] = {2, 0, 1, 1, 0, 2};
    cv::mixChannels(&scratch, 1, planes, 3, bgr_to_rgb, 3);
}

double dark_image_gain(const cv::Mat3b& bgr, cv::Mat1b& grey)
{
    if (bgr.empty()) return 1.0;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    std::array<int, 256> histogram{};
    for (int y = 0; y < grey.rows; ++y) {
        const uchar* row = grey.ptr<uchar>(y);
        for (int x = 0; x < grey.cols; ++x) ++histogram[row[x]];
    }
    // Blown-out pixels (a window, a lamp) say nothing of how the rest is exposed: left out.
    int level = 255, judged = int(grey.total());
    for (; level >= kBlownOutLevel; --level) judged -= histogram[std::size_t(level)];
    if (judged == 0) return 1.0;
    const int above = judged / 20;  // pixels above the 95th percentile
    int count = 0;
    while (level > 0 && count + histogram[std::size_t(level)] <= above) count += histogram[std::size_t(level--)];
    if (level >= kDarkBrightEnd) return 1.0;
    return std::min(kMaxDarkGain, double(kExposedBrightEnd) / std::max(level, 1));
}

void brighten_if_dark(cv::Mat3b& bgr, cv::Mat1b& grey)
{
    const double gain = dark_image_gain(bgr, grey);
    if (gain != 1.0) bgr.convertTo(bgr, -1, gain);
}

}  // namespace gc
