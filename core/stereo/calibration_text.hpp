// The product's own reader for calibration files: the subset of OpenCV FileStorage YAML and
// XML that a calibration uses (top-level numbers and opencv-matrix nodes), read strictly.
// Untrusted text never reaches cv::FileStorage, whose 4.6 parsers hang or crash on some
// malformed input; this reader is a single linear pass without recursion and with bounded
// sizes. The accepted syntax is described in docs/calibration.md.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace gc {

struct CalibrationScalar {
    double value = 0.0;
    bool integral = false;  // written without a fraction or exponent, e.g. "640"
};

struct CalibrationMatrix {
    int rows = 0;
    int cols = 0;
    char dt = 'd';             // OpenCV's element type letter as stored (u c w s i f d)
    std::vector<double> data;  // row-major, rows * cols values
};

// A double-quoted text value, as FileStorage writes strings (e.g. a calibration time). No
// calibration field is text: it is kept only so that a field given as text is reported as such.
struct CalibrationText {
    std::string text;
};

struct CalibrationEntry {
    std::size_t line = 0;  // where the key is, for messages
    std::variant<CalibrationScalar, CalibrationMatrix, CalibrationText> value;
};

using CalibrationEntries = std::map<std::string, CalibrationEntry, std::less<>>;

inline constexpr std::size_t kCalibrationMaxLineBytes = 64 * 1024;
inline constexpr std::size_t kCalibrationMaxMatrixValues = 10000;

// Reads the top-level keys of a YAML (`%YAML:1.0`) or XML (`<?xml ...?>`) calibration text,
// recognised from its first line. Throws CalibrationError naming `source`, the line and,
// where there is one, the key: for lines over kCalibrationMaxLineBytes, matrices of more than
// kCalibrationMaxMatrixValues values or whose data count differs from rows x cols, nesting
// other than an opencv-matrix node, an unknown dt, a token that is not a number, a
// duplicate key, and any other syntax outside the subset.
CalibrationEntries read_calibration_text(std::string_view text, const std::string& source);

}  // namespace gc
