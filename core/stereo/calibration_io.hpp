// Parsing a calibration from memory: the loader's core, shared by load_calibration and the
// fuzz target (which feeds arbitrary bytes without touching the file system).
#pragma once

#include "stereo/calibration.hpp"

#include <string>

namespace gc {

// `content` is the text of a calibration file (YAML or XML as cv::FileStorage writes it, read by
// the strict reader of stereo/calibration_text.hpp);
// `source` names it in messages and becomes StereoCalibration::source. Same validation and
// errors as load_calibration.
StereoCalibration parse_calibration(const std::string& content, const std::string& source);

// The checks load_calibration applies to the fields, for calibrations built in code
// (e.g. by gesturecam-calibrate before saving). Throws CalibrationError naming the field.
void validate_calibration(const StereoCalibration& calibration);

}  // namespace gc
