#include "tracking_overlay.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace gc::gst {
namespace {

constexpr int kBinPx = 4;              // histogram bin width, pixels
constexpr double kBarFraction = 0.12;  // the tallest bar, as a fraction of the frame size

const cv::Scalar kContourColour(0, 255, 0);
const cv::Scalar kRayColour(0, 200, 255);
const cv::Scalar kMarginalColour(255, 160, 0);

cv::Scalar state_colour(TrackState s)
{
    switch (s) {
    case TrackState::Tracking:
        return {0, 255, 0};
    case TrackState::Lost:
        return {0, 0, 255};
    case TrackState::Acquiring:
        break;
    }
    return {0, 255, 255};
}

}  // namespace

void TrackingOverlay::draw_marginals(cv::Mat& bgr, std::span<const Particle> particles)
{
    x_bins_.assign(static_cast<size_t>(bgr.cols / kBinPx + 1), 0.0);
    y_bins_.assign(static_cast<size_t>(bgr.rows / kBinPx + 1), 0.0);
    for (const Particle& p : particles) {
        if (!std::isfinite(p.state.x) || !std::isfinite(p.state.y) || !(p.weight > 0.0)) continue;
        const int bx = int(std::floor(p.state.x / kBinPx));
        const int by = int(std::floor(p.state.y / kBinPx));
        if (bx >= 0 && bx < int(x_bins_.size())) x_bins_[size_t(bx)] += p.weight;
        if (by >= 0 && by < int(y_bins_.size())) y_bins_[size_t(by)] += p.weight;
    }
    const double x_max = *std::max_element(x_bins_.begin(), x_bins_.end());
    const double y_max = *std::max_element(y_bins_.begin(), y_bins_.end());
    if (x_max > 0.0) {
        const double height = kBarFraction * bgr.rows;
        for (size_t i = 0; i < x_bins_.size(); ++i) {
            const int len = int(std::lround(height * x_bins_[i] / x_max));
            if (len > 0)
                cv::rectangle(bgr, cv::Point(int(i) * kBinPx, bgr.rows - len),
                              cv::Point(int(i) * kBinPx + kBinPx - 2, bgr.rows - 1), kMarginalColour, cv::FILLED);
        }
    }
    if (y_max > 0.0) {
        const double width = kBarFraction * bgr.cols;
        for (size_t i = 0; i < y_bins_.size(); ++i) {
            const int len = int(std::lround(width * y_bins_[i] / y_max));
            if (len > 0)
                cv::rectangle(bgr, cv::Point(bgr.cols - len, int(i) * kBinPx),
                              cv::Point(bgr.cols - 1, int(i) * kBinPx + kBinPx - 2), kMarginalColour, cv::FILLED);
        }
    }
}

void TrackingOverlay::draw(cv::Mat& bgr, const EyeEstimate& eye, std::span<const Particle> particles,
                           const Pointing3D* pointing)
{
    if (bgr.empty()) return;
    if (!particles.empty()) draw_marginals(bgr, particles);

    if (eye.state != TrackState::Acquiring && eye.contour.size() >= 3) {
        polygon_.clear();
        for (const cv::Point2f& p : eye.contour) polygon_.emplace_back(int(std::lround(p.x)), int(std::lround(p.y)));
        cv::polylines(bgr, polygon_, true, state_colour(eye.state), 2, cv::LINE_AA);
    }
    if (eye.valid()) {
        // The pointing direction in the image: from the fingertip to the frame border
        // (pointing_deg has y up, the image has y down).
        const double a = eye.pointing_deg * std::numbers::pi / 180.0;
        const cv::Point tip(int(std::lround(eye.fingertip.x)), int(std::lround(eye.fingertip.y)));
        const double reach = bgr.cols + bgr.rows;
        cv::Point far(int(std::lround(eye.fingertip.x + reach * std::cos(a))),
                      int(std::lround(eye.fingertip.y - reach * std::sin(a))));
        cv::Point from = tip;
        if (cv::clipLine(bgr.size(), from, far)) cv::line(bgr, from, far, kRayColour, 2, cv::LINE_AA);
        cv::circle(bgr, tip, 5, kRayColour, 2, cv::LINE_AA);
        cv::drawMarker(bgr, cv::Point(int(std::lround(eye.palm.x)), int(std::lround(eye.palm.y))), kContourColour,
                       cv::MARKER_CROSS, 12, 2);
    }

    // The gesture is named only where the key points told it (the learned detector).
    const char* gesture = eye.gesture == Gesture::Unknown ? "" : to_string(eye.gesture).data();
    char text[192];
    if (pointing && pointing->valid)
        std::snprintf(text, sizeof text, "%s %.2f %s  az %+.1f el %+.1f deg  z %.0f mm", to_string(eye.state).data(),
                      eye.confidence, gesture, pointing->azimuth_deg, pointing->elevation_deg,
                      pointing->fingertip_mm[2]);
    else
        std::snprintf(text, sizeof text, "%s %.2f %s", to_string(eye.state).data(), eye.confidence, gesture);
    const double font = std::max(0.4, bgr.rows / 800.0);
    cv::putText(bgr, text, cv::Point(8, int(24 * font / 0.6)), cv::FONT_HERSHEY_SIMPLEX, font, cv::Scalar(0, 0, 0), 3,
                cv::LINE_AA);
    cv::putText(bgr, text, cv::Point(8, int(24 * font / 0.6)), cv::FONT_HERSHEY_SIMPLEX, font, state_colour(eye.state),
                1, cv::LINE_AA);
}

}  // namespace gc::gst
