#include "tracker/analysis_scale.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace gc {

namespace {

// A pixel-centre coordinate (centres at integers) from one grid to another.
double rescale_centre(double v, double s) { return (v + 0.5) * s - 0.5; }

cv::Point2f to_frame(const cv::Point2f& p, const AnalysisScale& a)
{
    return {static_cast<float>(rescale_centre(p.x, 1.0 / a.sx)), static_cast<float>(rescale_centre(p.y, 1.0 / a.sy))};
}

void to_frame(HandState& s, const AnalysisScale& a)
{
    s.x = rescale_centre(s.x, 1.0 / a.sx);
    s.y = rescale_centre(s.y, 1.0 / a.sy);
}

cv::Matx33d scaled_intrinsics(const cv::Matx33d& M, const AnalysisScale& a)
{
    cv::Matx33d out = M;
    out(0, 0) *= a.sx;
    out(0, 1) *= a.sx;
    out(0, 2) = rescale_centre(M(0, 2), a.sx);
    out(1, 1) *= a.sy;
    out(1, 2) = rescale_centre(M(1, 2), a.sy);
    return out;
}

}  // namespace

AnalysisScale analysis_scale(cv::Size frame, int max_width)
{
    AnalysisScale a;
    a.frame = a.analysed = frame;
    if (max_width <= 0) return a;
    // No smaller than the tracker's smallest frame on either side.
    const double s = std::max(
        {double(std::max(max_width, kMinTrackingWidth)) / frame.width, double(kMinTrackingHeight) / frame.height});
    if (s >= 1.0) return a;
    a.analysed.width = static_cast<int>(std::lround(frame.width * s));
    a.analysed.height = static_cast<int>(std::lround(frame.height * s));
    a.sx = double(a.analysed.width) / frame.width;
    a.sy = double(a.analysed.height) / frame.height;
    return a;
}

void downscale(const cv::Mat& frame, cv::Size to, DownscaleBuffers& buffers, cv::Mat& out)
{
    const cv::Mat* current = &frame;
    int next = 0;
    while (current->cols >= 2 * to.width && current->rows >= 2 * to.height) {
        cv::Mat& half = buffers.halves[next];
        cv::resize(*current, half, cv::Size(current->cols / 2, current->rows / 2), 0.0, 0.0, cv::INTER_AREA);
        current = &half;
        next = 1 - next;
    }
    cv::resize(*current, out, to, 0.0, 0.0, cv::INTER_LINEAR);
}

StereoCalibration scaled_calibration(const StereoCalibration& calibration, const AnalysisScale& scale)
{
    StereoCalibration out = calibration;
    out.D1 = calibration.D1.clone();
    out.D2 = calibration.D2.clone();
    out.image_size = scale.analysed;
    out.M1 = scaled_intrinsics(calibration.M1, scale);
    out.M2 = scaled_intrinsics(calibration.M2, scale);
    return out;
}

ImageMotion to_analysed(const ImageMotion& motion, const AnalysisScale& scale)
{
    ImageMotion out = motion;
    out.dx *= scale.sx;
    out.dy *= scale.sy;
    return out;
}

void to_frame(EyeEstimate& e, const AnalysisScale& a)
{
    // Without a contour the estimate is none (acquiring, lost): its fields stay as they are.
    if (!a.active() || e.contour.empty()) return;
    to_frame(e.mean, a);
    to_frame(e.best, a);
    for (cv::Point2f& p : e.contour) p = to_frame(p, a);
    for (cv::Point2f& p : e.landmarks) p = to_frame(p, a);
    e.fingertip = to_frame(e.fingertip, a);
    e.palm = to_frame(e.palm, a);
    e.bbox = cv::boundingRect(e.contour);  // as the tracker makes it, from the contour
}

void to_frame(std::span<const Particle> particles, const AnalysisScale& scale, std::vector<Particle>& out)
{
    out.assign(particles.begin(), particles.end());
    for (Particle& p : out) to_frame(p.state, scale);
}

}  // namespace gc
