// Loading, validating and saving the stereo calibration file (format in docs/calibration.md).
#include "stereo/calibration_io.hpp"

#include "common/small_file.hpp"
#include "stereo/calibration_text.hpp"

#include <opencv2/core/persistence.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string_view>
#include <variant>

namespace gc {

namespace {

// A calibration never needs a larger matrix; checking before OpenCV allocates keeps a
// corrupt "rows: 1000000000" from exhausting memory.
constexpr int kMaxMatrixSide = 16;
constexpr int kMaxImageSide = 1 << 15;
// Tolerance on R^T R - I: files written with six significant digits stay well inside it.
constexpr double kRotationTolerance = 1e-4;
// A calibration file is a few kilobytes; the cap keeps /dev/zero or a huge file of unknown
// keys from being read into memory.
constexpr std::size_t kMaxFileBytes = std::size_t{1} << 20;
// Physical plausibility. Focal lengths relative to the image width: 0.1 is a field of view
// of 157 degrees, 20 one of 2.9 degrees; no camera that can track a hand lies outside.
constexpr double kMinFocalPerWidth = 0.1;
constexpr double kMaxFocalPerWidth = 20.0;
// Baseline |T|: a stereo pair closer than 10 mm cannot triangulate a hand, one wider than
// 10 m is a unit error (T is in millimetres).
constexpr double kMinBaselineMm = 10.0;
constexpr double kMaxBaselineMm = 10000.0;
// Distortion coefficients of real lenses stay within a few tens even in the rational model.
constexpr double kMaxDistortionCoefficient = 100.0;

[[noreturn]] void fail(const std::string& source, std::string_view key, const std::string& what)
{
    std::ostringstream msg;
    msg << "calibration file '" << source << "': ";
    if (!key.empty()) msg << "key '" << key << "': ";
    msg << what;
    throw CalibrationError(msg.str());
}

std::string shape_string(int rows, int cols) { return std::to_string(rows) + "x" + std::to_string(cols); }

bool all_finite(const cv::Mat& m) { return cv::checkRange(m, true, nullptr, -1e12, 1e12); }

const CalibrationEntry* find_entry(const CalibrationEntries& entries, std::string_view key)
{
    const auto it = entries.find(key);
    return it == entries.end() ? nullptr : &it->second;
}

// Reads `key` as a CV_64F matrix after checking that the entry really is one of a sane size.
cv::Mat read_matrix(const CalibrationEntries& entries, const char* key, const std::string& source,
                    bool allow_empty = false)
{
    const CalibrationEntry* entry = find_entry(entries, key);
    if (!entry) fail(source, key, "missing");
    const auto* matrix = std::get_if<CalibrationMatrix>(&entry->value);
    if (!matrix) fail(source, key, "not a matrix (expected an opencv-matrix node)");
    const int rows = matrix->rows, cols = matrix->cols;
    if (rows > kMaxMatrixSide || cols > kMaxMatrixSide)
        fail(source, key, "implausible matrix size " + shape_string(rows, cols));
    if (rows * cols == 0) {
        if (allow_empty) return {};
        fail(source, key, "empty matrix");
    }
    cv::Mat d(rows, cols, CV_64F);
    std::copy(matrix->data.begin(), matrix->data.end(), d.begin<double>());
    if (!all_finite(d)) fail(source, key, "non-finite or absurdly large value");
    return d;
}

cv::Mat expect_shape(cv::Mat m, const char* key, const std::string& source, int rows, int cols)
{
    if (m.rows == rows && m.cols == cols) return m;
    // A vector may be stored as a row or a column.
    if (cols == 1 && m.rows == 1 && m.cols == rows) return m.t();
    fail(source, key, "wrong shape " + shape_string(m.rows, m.cols) + ", expected " + shape_string(rows, cols));
}

int read_positive_int(const CalibrationEntries& entries, const char* key, const std::string& source)
{
    const CalibrationEntry* entry = find_entry(entries, key);
    if (!entry) fail(source, key, "missing");
    const auto* scalar = std::get_if<CalibrationScalar>(&entry->value);
    if (!scalar || !scalar->integral) fail(source, key, "not an integer");
    const double v = scalar->value;
    if (!(v >= 1.0 && v <= kMaxImageSide)) {
        std::ostringstream what;
        what << "out of range: " << v << " (expected 1.." << kMaxImageSide << ")";
        fail(source, key, what.str());
    }
    return static_cast<int>(v);
}

std::string number_text(double v)
{
    std::ostringstream text;
    text << v;
    return text.str();
}

// `name` = `v` must lie in [lo, hi]; the message gives the value and the range.
void check_range(double v, double lo, double hi, const char* key, const std::string& name, const std::string& source,
                 const std::string& why)
{
    if (v >= lo && v <= hi) return;
    fail(source, key,
         name + " = " + number_text(v) + " is implausible: expected " + number_text(lo) + " to " + number_text(hi) +
             " " + why);
}

void check_intrinsics(const cv::Matx33d& M, const char* key, const std::string& source, cv::Size image)
{
    for (double v : M.val)
        if (!std::isfinite(v)) fail(source, key, "non-finite value");
    const std::string size = " for " + std::to_string(image.width) + "x" + std::to_string(image.height) + " images";
    const double w = image.width;
    check_range(M(0, 0), kMinFocalPerWidth * w, kMaxFocalPerWidth * w, key, "focal length fx", source,
                "px (0.1 to 20 image widths)" + size);
    check_range(M(1, 1), kMinFocalPerWidth * w, kMaxFocalPerWidth * w, key, "focal length fy", source,
                "px (0.1 to 20 image widths)" + size);
    check_range(M(0, 2), 0.0, w, key, "principal point cx", source, "px (inside the image)" + size);
    check_range(M(1, 2), 0.0, image.height, key, "principal point cy", source, "px (inside the image)" + size);
    check_range(M(0, 1), -M(0, 0), M(0, 0), key, "skew", source, "px (at most fx in magnitude)");
    if (M(1, 0) != 0.0 || M(2, 0) != 0.0 || M(2, 1) != 0.0 || M(2, 2) != 1.0)
        fail(source, key, "not an intrinsic matrix (expected [fx s cx; 0 fy cy; 0 0 1])");
}

void check_distortion(const cv::Mat& D, const char* key, const std::string& source)
{
    if (D.empty()) return;
    const int n = static_cast<int>(D.total());
    if ((D.rows != 1 && D.cols != 1) || (n != 4 && n != 5 && n != 8 && n != 12 && n != 14))
        fail(source, key, "wrong shape " + shape_string(D.rows, D.cols) + ", expected 1xN with N = 4, 5, 8, 12 or 14");
    if (D.type() != CV_64F || !all_finite(D)) fail(source, key, "non-finite value");
    for (int i = 0; i < n; ++i)
        check_range(D.at<double>(i), -kMaxDistortionCoefficient, kMaxDistortionCoefficient, key,
                    "coefficient " + std::to_string(i + 1) + " of " + std::to_string(n), source,
                    "(OpenCV order k1 k2 p1 p2 k3 ...)");
}

// Distortion as stored (a row or a column), checked, then as the 1xN row OpenCV expects.
cv::Mat read_distortion(const CalibrationEntries& entries, const char* key, const std::string& source)
{
    const cv::Mat D = read_matrix(entries, key, source, true);
    check_distortion(D, key, source);
    return D.empty() ? D : D.reshape(1, 1);
}

void check_rotation(const cv::Matx33d& R, const std::string& source, const char* key = "R")
{
    for (double v : R.val)
        if (!std::isfinite(v)) fail(source, key, "non-finite value");
    const double orthogonality = cv::norm(R.t() * R - cv::Matx33d::eye(), cv::NORM_INF);
    const double det = cv::determinant(R);
    if (orthogonality > kRotationTolerance || std::abs(det - 1.0) > kRotationTolerance) {
        std::ostringstream what;
        what << "not a rotation matrix (max |R^T R - I| = " << orthogonality << ", det = " << det << ")";
        fail(source, key, what.str());
    }
}

void check_translation(const cv::Vec3d& T, const std::string& source)
{
    for (double v : T.val)
        if (!std::isfinite(v)) fail(source, "T", "non-finite value");
    check_range(cv::norm(T), kMinBaselineMm, kMaxBaselineMm, "T", "baseline |T|", source, "mm (T is in millimetres)");
}

constexpr std::array<const char*, 4> kHeadKeys{"head_left_eye", "head_right_eye", "head_tilt_centre",
                                               "head_nodal_offset"};

constexpr std::array<const char*, 5> kDirectorKeys{"director_image_width", "director_image_height", "director_M",
                                                   "director_R", "director_T"};
// A director camera further than this from the rig is a unit error (millimetres).
constexpr double kMaxDirectorDistanceMm = 100000.0;

void check_director(const DirectorMount& d, const std::string& source)
{
    check_intrinsics(d.K, "director_M", source, d.image_size);
    check_rotation(d.head_to_base.R, source, "director_R");
    for (double v : d.head_to_base.t.val)
        if (!std::isfinite(v)) fail(source, "director_T", "non-finite value");
    check_range(cv::norm(d.head_to_base.t), 0.0, kMaxDirectorDistanceMm, "director_T", "|director_T|", source,
                "mm (director_T is in millimetres)");
}

std::optional<DirectorMount> read_director(const CalibrationEntries& root, const std::string& source)
{
    int present = 0;
    for (const char* key : kDirectorKeys) present += root.contains(key);
    if (present == 0) return std::nullopt;
    for (const char* key : kDirectorKeys)
        if (!root.contains(key)) fail(source, key, "missing (the director keys come all together or not at all)");
    DirectorMount d;
    d.image_size.width = read_positive_int(root, kDirectorKeys[0], source);
    d.image_size.height = read_positive_int(root, kDirectorKeys[1], source);
    d.K = cv::Matx33d(expect_shape(read_matrix(root, kDirectorKeys[2], source), kDirectorKeys[2], source, 3, 3));
    d.head_to_base.R =
        cv::Matx33d(expect_shape(read_matrix(root, kDirectorKeys[3], source), kDirectorKeys[3], source, 3, 3));
    d.head_to_base.t =
        cv::Vec3d(expect_shape(read_matrix(root, kDirectorKeys[4], source), kDirectorKeys[4], source, 3, 1));
    check_director(d, source);
    return d;
}

HeadGeometry geometry_from_baseline(const cv::Vec3d& T)
{
    HeadGeometry g;
    const double half = 0.5 * cv::norm(T);
    g.left_eye_mm = {-half, 0.0, 0.0};
    g.right_eye_mm = {half, 0.0, 0.0};
    return g;
}

StereoCalibration read_fields(const CalibrationEntries& root, const std::string& source)
{
    StereoCalibration c;
    c.source = source;
    c.image_size.width = read_positive_int(root, "image_width", source);
    c.image_size.height = read_positive_int(root, "image_height", source);
    c.M1 = cv::Matx33d(expect_shape(read_matrix(root, "M1", source), "M1", source, 3, 3));
    check_intrinsics(c.M1, "M1", source, c.image_size);
    c.D1 = read_distortion(root, "D1", source);
    c.M2 = cv::Matx33d(expect_shape(read_matrix(root, "M2", source), "M2", source, 3, 3));
    check_intrinsics(c.M2, "M2", source, c.image_size);
    c.D2 = read_distortion(root, "D2", source);
    c.R = cv::Matx33d(expect_shape(read_matrix(root, "R", source), "R", source, 3, 3));
    check_rotation(c.R, source);
    c.T = cv::Vec3d(expect_shape(read_matrix(root, "T", source), "T", source, 3, 1));
    check_translation(c.T, source);
    c.director = read_director(root, source);

    int present = 0;
    for (const char* key : kHeadKeys) present += root.contains(key);
    if (present == 0) {
        c.has_head_geometry = false;
        c.head = geometry_from_baseline(c.T);
        return c;
    }
    std::array<cv::Vec3d, 4> v;
    for (size_t i = 0; i < kHeadKeys.size(); ++i) {
        if (!root.contains(kHeadKeys[i]))
            fail(source, kHeadKeys[i], "missing (the head geometry keys come all together or not at all)");
        v[i] = cv::Vec3d(expect_shape(read_matrix(root, kHeadKeys[i], source), kHeadKeys[i], source, 3, 1));
    }
    c.has_head_geometry = true;
    c.head.left_eye_mm = v[0];
    c.head.right_eye_mm = v[1];
    c.head.tilt_centre_mm = v[2];
    c.head.nodal_offset_mm = v[3];
    if (c.head.baseline_mm() < 1.0) fail(source, "head_right_eye", "the eye centres coincide");
    return c;
}

}  // namespace

StereoCalibration parse_calibration(const std::string& content, const std::string& source)
{
    if (content.empty()) fail(source, "", "empty file");
    // The product's reader, not cv::FileStorage: OpenCV 4.6's parsers hang or crash on some
    // malformed files, and a calibration file is untrusted input.
    return read_fields(read_calibration_text(content, source), source);
}

StereoCalibration load_calibration(const std::string& path)
{
    std::string content;
    try {
        content = read_small_file(path, kMaxFileBytes);
    } catch (const SmallFileError& e) {
        fail(path, "", e.what());
    }
    return parse_calibration(content, path);
}

void validate_calibration(const StereoCalibration& c)
{
    const std::string& source = c.source;
    if (c.image_size.width <= 0 || c.image_size.width > kMaxImageSide) fail(source, "image_width", "out of range");
    if (c.image_size.height <= 0 || c.image_size.height > kMaxImageSide) fail(source, "image_height", "out of range");
    check_intrinsics(c.M1, "M1", source, c.image_size);
    check_distortion(c.D1, "D1", source);
    check_intrinsics(c.M2, "M2", source, c.image_size);
    check_distortion(c.D2, "D2", source);
    check_rotation(c.R, source);
    check_translation(c.T, source);
    if (c.has_head_geometry) {
        const std::array<cv::Vec3d, 4> v{c.head.left_eye_mm, c.head.right_eye_mm, c.head.tilt_centre_mm,
                                         c.head.nodal_offset_mm};
        for (size_t i = 0; i < v.size(); ++i)
            for (double x : v[i].val)
                if (!std::isfinite(x)) fail(source, kHeadKeys[i], "non-finite value");
    }
    if (c.director) check_director(*c.director, source);
}

void validate_calibration_size(const StereoCalibration& c, cv::Size stream)
{
    if (c.image_size == stream) return;
    std::ostringstream what;
    what << "calibrated for " << c.image_size.width << "x" << c.image_size.height << " images but the stream is "
         << stream.width << "x" << stream.height;
    fail(c.source, "image_width/image_height", what.str());
}

void save_calibration(const StereoCalibration& c, const std::string& path)
{
    validate_calibration(c);
    try {
        cv::FileStorage fs(path, cv::FileStorage::WRITE);
        if (!fs.isOpened()) fail(path, "", "cannot be opened for writing");
        fs.writeComment("GestureCAM stereo calibration: X_right = R * X_left + T, millimetres");
        fs << "image_width" << c.image_size.width << "image_height" << c.image_size.height;
        // No distortion is written as five zeros, the form every OpenCV reader expects.
        const cv::Mat no_distortion = cv::Mat::zeros(1, 5, CV_64F);
        fs << "M1" << cv::Mat(c.M1) << "D1" << (c.D1.empty() ? no_distortion : c.D1);
        fs << "M2" << cv::Mat(c.M2) << "D2" << (c.D2.empty() ? no_distortion : c.D2);
        fs << "R" << cv::Mat(c.R) << "T" << cv::Mat(c.T);
        if (c.has_head_geometry) {
            fs << kHeadKeys[0] << cv::Mat(c.head.left_eye_mm) << kHeadKeys[1] << cv::Mat(c.head.right_eye_mm);
            fs << kHeadKeys[2] << cv::Mat(c.head.tilt_centre_mm) << kHeadKeys[3] << cv::Mat(c.head.nodal_offset_mm);
        }
        if (const auto& d = c.director) {
            fs << kDirectorKeys[0] << d->image_size.width << kDirectorKeys[1] << d->image_size.height;
            fs << kDirectorKeys[2] << cv::Mat(d->K) << kDirectorKeys[3] << cv::Mat(d->head_to_base.R);
            fs << kDirectorKeys[4] << cv::Mat(d->head_to_base.t);
        }
        fs.release();
    } catch (const cv::Exception& e) {
        fail(path, "", std::string("write failed: ") + e.what());
    }
}

}  // namespace gc
