// The nominal rig: what the product assumes when no calibration file is given.
#include "stereo/calibration.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace gc {

namespace {
constexpr double kBaselineMm = 120.0;
constexpr double kHorizontalFovDeg = 60.0;
}  // namespace

StereoCalibration default_calibration(cv::Size image_size)
{
    if (image_size.width <= 0 || image_size.height <= 0)
        throw CalibrationError("default calibration: image size " + std::to_string(image_size.width) + "x" +
                               std::to_string(image_size.height) + " is not positive");
    const double f = 0.5 * image_size.width / std::tan(0.5 * kHorizontalFovDeg * std::numbers::pi / 180.0);
    // Principal point at the centre of the pixel grid (pixel centres at integer coordinates).
    const double cx = 0.5 * (image_size.width - 1), cy = 0.5 * (image_size.height - 1);
    const cv::Matx33d M{f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0};

    StereoCalibration c;
    c.image_size = image_size;
    c.M1 = M;
    c.M2 = M;
    c.D1 = cv::Mat();
    c.D2 = cv::Mat();
    c.R = cv::Matx33d::eye();
    c.T = {-kBaselineMm, 0.0, 0.0};  // the right camera sits +120 mm along the left's x axis
    c.has_head_geometry = true;
    c.head = HeadGeometry{};
    c.head.left_eye_mm = {-0.5 * kBaselineMm, 0.0, 0.0};
    c.head.right_eye_mm = {0.5 * kBaselineMm, 0.0, 0.0};
    c.source = "default";
    return c;
}

}  // namespace gc
