// The stereo calibration file (OpenCV FileStorage, YAML or XML; docs/calibration.md):
// image_width, image_height, M1, D1, M2, D2, R, T (X_right = R X_left + T, millimetres),
// as cv::stereoCalibrate writes them; head geometry optional.
#pragma once

#include "stereo/director_mount.hpp"
#include "stereo/head_geometry.hpp"

#include <opencv2/core.hpp>

#include <optional>
#include <stdexcept>
#include <string>

namespace gc {

struct StereoCalibration {
    cv::Size image_size;
    cv::Matx33d M1 = cv::Matx33d::eye();  // left intrinsics
    cv::Mat D1;                           // left distortion, 1xN CV_64F (N = 4, 5, 8, 12, 14), may be empty
    cv::Matx33d M2 = cv::Matx33d::eye();  // right intrinsics
    cv::Mat D2;
    cv::Matx33d R = cv::Matx33d::eye();  // at the head's zero pose
    cv::Vec3d T{-120.0, 0.0, 0.0};
    bool has_head_geometry = false;
    HeadGeometry head;
    std::optional<DirectorMount> director;  // a second PTZ camera framing picked targets
    std::string source = "default";         // the file it came from, for messages
};

// Raised with a message that names the file and the key at fault.
class CalibrationError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads a calibration file (YAML or XML, told apart by the first line) and validates
// it fully: a regular file of at most 1 MiB (a FIFO or device is refused without blocking),
// every required key present, matrices of the right shape and finite, R a proper rotation, a
// positive image size, distortion of a length OpenCV accepts, and physically plausible values
// (focal lengths 0.1 to 20 image widths, the principal point inside the image, a baseline of
// 10 mm to 10 m, distortion coefficients within +-100). The optional head
// geometry keys are head_left_eye, head_right_eye, head_tilt_centre, head_nodal_offset
// (3x1, millimetres, head frame); when absent, the geometry is derived from T (eyes at
// -/+ |T| / 2 on the x axis). The optional director keys (all or none) place a second PTZ
// camera: director_image_width, director_image_height, director_M (its intrinsics at the
// widest zoom, checked as M1 is), director_R and director_T (X_base = R X_head + T,
// millimetres, R a rotation, |T| at most 100 m). Throws CalibrationError naming the file and
// the key.
StereoCalibration load_calibration(const std::string& path);

// Throws CalibrationError naming both sizes when the stream size differs from the
// calibrated one.
void validate_calibration_size(const StereoCalibration& calibration, cv::Size stream);

// Writes every field load_calibration reads (head geometry and director only when set); the
// format follows the extension (.yml/.yaml or .xml). Throws CalibrationError on failure.
void save_calibration(const StereoCalibration& calibration, const std::string& path);

// The rig's nominal geometry: 120 mm baseline, 60 degree horizontal field of view, square
// pixels, principal point at the image centre, no distortion, parallel cameras at the zero
// pose, head geometry with the eyes at -/+60 mm on the x axis. Throws CalibrationError on a
// non-positive size.
StereoCalibration default_calibration(cv::Size image_size);

}  // namespace gc
