// The stereo calibration file (OpenCV FileStorage, YAML or XML), fixed in DESIGN.md:
// image_width, image_height, M1, D1, M2, D2, R, T (X_right = R X_left + T, millimetres),
// as cv::stereoCalibrate writes them; head geometry optional.
#pragma once

#include "stereo/head_geometry.hpp"

#include <opencv2/core.hpp>

#include <stdexcept>
#include <string>

namespace gc {

struct StereoCalibration {
    cv::Size image_size;
    cv::Matx33d M1 = cv::Matx33d::eye();  // left intrinsics
    cv::Mat D1;                           // left distortion, 1xN CV_64F (N = 4, 5, 8, 12, 14), may be empty
    cv::Matx33d M2 = cv::Matx33d::eye();  // right intrinsics
    cv::Mat D2;
    cv::Matx33d R = cv::Matx33d::eye();   // at the head's zero pose
    cv::Vec3d T{-120.0, 0.0, 0.0};
    bool has_head_geometry = false;
    HeadGeometry head;
    std::string source = "default";       // the file it came from, for messages
};

// Raised with a message that names the file and the key at fault.
class CalibrationError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace gc
