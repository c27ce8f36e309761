// gesturecam-calibrate: stereo calibration of the camera pair from chessboard image pairs.
// Writes the calibration file of docs/calibration.md and prints the RMS reprojection error
// and the mean epipolar error of the detected corners.
#include "stereo/calibration.hpp"
#include "stereo/calibration_io.hpp"
#include "tools/cli_app.hpp"
#include "tools/image_file.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr int kMaxPatternIndex = 9999;
constexpr int kMinPairs = 3;

const char* const kUsage =
    "usage: gesturecam-calibrate --left SPEC --right SPEC [options]\n"
    "  --left SPEC, --right SPEC  images of the left / right camera: a printf pattern such as\n"
    "                             'left%02d.jpg' (every index 0..9999 whose pair exists), or a\n"
    "                             comma-separated list of files; may be repeated\n"
    "  --board WxH                inner corners of the chessboard (default 9x6)\n"
    "  --square MM                side of one square in millimetres (default 25)\n"
    "  --out FILE                 calibration file to write, .yml or .xml (default calibration.yml)\n"
    "  --verbose                  print each pair's detection result\n"
    "  --version                  the version\n"
    "  -h, --help                 this text\n";

struct Options {
    std::vector<std::string> left, right;
    cv::Size board{9, 6};
    double square_mm = 25.0;
    std::string out = "calibration.yml";
    bool verbose = false;
};

using gc::cli::UsageError;

cv::Size parse_board(const std::string& s)
{
    int w = 0, h = 0;
    char x = 0, extra = 0;
    std::istringstream in(s);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w < 2 || h < 2 || w > 100 || h > 100)
        throw UsageError("--board: expected WxH inner corners, each 2..100, got '" + s + "'");
    return {w, h};
}

double parse_square(const std::string& s)
{
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(s, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != s.size() || !(v > 0.0) || !std::isfinite(v))
        throw UsageError("--square: expected a positive length in millimetres, got '" + s + "'");
    return v;
}

// Parses the command line into `o`: -1 to go on, else the status to exit with.
int parse(int argc, char** argv, Options& o)
{
    std::string board, square;
    CLI::App app("Stereo calibration of the camera pair from chessboard image pairs", "gesturecam-calibrate");
    gc::cli::configure(app, kUsage);
    app.add_option("--left", o.left)->required()->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--right", o.right)->required()->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--board", board);
    app.add_option("--square", square);
    app.add_option("--out", o.out);
    app.add_flag("--verbose", o.verbose);
    if (const int status = gc::cli::parse(app, argc, argv); status >= 0) return status;
    try {
        if (!board.empty()) o.board = parse_board(board);
        if (!square.empty()) o.square_mm = parse_square(square);
    } catch (const UsageError& e) {
        return gc::cli::usage_hint("gesturecam-calibrate", e.what());
    }
    return -1;
}

bool is_pattern(const std::string& s) { return s.find('%') != std::string::npos; }

// A pattern must hold exactly one integer conversion (%d, %02d, ...): anything else given
// to snprintf would read arguments that are not there.
void check_pattern(const std::string& pattern)
{
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
        if (j >= pattern.size() || pattern[j] != 'd' || j - i > 4)
            throw UsageError("pattern '" + pattern + "': only integer conversions such as %02d are allowed");
        ++conversions;
        i = j;
    }
    if (conversions != 1) throw UsageError("pattern '" + pattern + "' must hold exactly one %d conversion");
}

std::string format_index(const std::string& pattern, int index)
{
    check_pattern(pattern);
    std::vector<char> buf(pattern.size() + 32);
    const int n = std::snprintf(buf.data(), buf.size(), pattern.c_str(), index);
    if (n < 0 || static_cast<std::size_t>(n) >= buf.size()) throw UsageError("cannot format pattern '" + pattern + "'");
    return buf.data();
}

std::vector<std::string> split_list(const std::vector<std::string>& specs)
{
    std::vector<std::string> files;
    for (const std::string& spec : specs) {
        std::istringstream in(spec);
        std::string item;
        while (std::getline(in, item, ','))
            if (!item.empty()) files.push_back(item);
    }
    return files;
}

// Pairs of (left, right) file names. Patterns pair by index: an index is used when both
// files exist, so gaps in the numbering are fine.
std::vector<std::pair<std::string, std::string>> image_pairs(const Options& o)
{
    std::vector<std::pair<std::string, std::string>> pairs;
    if (o.left.size() == 1 && o.right.size() == 1 && is_pattern(o.left[0]) && is_pattern(o.right[0])) {
        for (int i = 0; i <= kMaxPatternIndex; ++i) {
            const std::string l = format_index(o.left[0], i), r = format_index(o.right[0], i);
            const bool hl = std::filesystem::exists(l), hr = std::filesystem::exists(r);
            if (hl && hr)
                pairs.emplace_back(l, r);
            else if (hl != hr)
                std::cerr << "warning: index " << i << ": only " << (hl ? l : r) << " exists, skipped\n";
        }
        if (pairs.empty())
            throw std::runtime_error("no image pair matches '" + o.left[0] + "' and '" + o.right[0] + "'");
        return pairs;
    }
    for (const auto& s : o.left)
        if (is_pattern(s)) throw UsageError("mixing patterns and lists: use one pattern per side or lists only");
    const auto left = split_list(o.left), right = split_list(o.right);
    if (left.size() != right.size())
        throw UsageError(std::to_string(left.size()) + " left images but " + std::to_string(right.size()) +
                         " right images");
    for (std::size_t i = 0; i < left.size(); ++i) pairs.emplace_back(left[i], right[i]);
    return pairs;
}

bool find_corners(const cv::Mat& grey, cv::Size board, std::vector<cv::Point2f>& corners)
{
    const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
    if (!cv::findChessboardCorners(grey, board, corners, flags)) return false;
    cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01));
    return true;
}

// Mean distance of each corner to the epipolar line of its partner, both directions, on
// undistorted points.
double mean_epipolar_error(const std::vector<std::vector<cv::Point2f>>& left,
                           const std::vector<std::vector<cv::Point2f>>& right, const gc::StereoCalibration& c,
                           const cv::Mat& F)
{
    double sum = 0.0;
    std::size_t count = 0;
    std::vector<cv::Point2f> ul, ur;
    std::vector<cv::Vec3f> ll, lr;
    for (std::size_t i = 0; i < left.size(); ++i) {
        cv::undistortPoints(left[i], ul, c.M1, c.D1, cv::noArray(), c.M1);
        cv::undistortPoints(right[i], ur, c.M2, c.D2, cv::noArray(), c.M2);
        cv::computeCorrespondEpilines(ul, 1, F, ll);  // lines in the right image
        cv::computeCorrespondEpilines(ur, 2, F, lr);  // lines in the left image
        for (std::size_t j = 0; j < ul.size(); ++j) {
            sum += std::abs(ur[j].x * ll[j][0] + ur[j].y * ll[j][1] + ll[j][2]);
            sum += std::abs(ul[j].x * lr[j][0] + ul[j].y * lr[j][1] + lr[j][2]);
            count += 2;
        }
    }
    return count ? sum / static_cast<double>(count) : 0.0;
}

int run(const Options& o)
{
    const auto pairs = image_pairs(o);
    std::vector<cv::Point3f> board_points;
    for (int y = 0; y < o.board.height; ++y)
        for (int x = 0; x < o.board.width; ++x)
            board_points.emplace_back(static_cast<float>(x * o.square_mm), static_cast<float>(y * o.square_mm), 0.0f);

    std::vector<std::vector<cv::Point3f>> object;
    std::vector<std::vector<cv::Point2f>> left_corners, right_corners;
    cv::Size size;
    std::vector<cv::Point2f> cl, cr;
    for (const auto& [lf, rf] : pairs) {
        const cv::Mat l = gc::tools::read_image_file(lf, cv::IMREAD_GRAYSCALE, "image '" + lf + "'");
        const cv::Mat r = gc::tools::read_image_file(rf, cv::IMREAD_GRAYSCALE, "image '" + rf + "'");
        if (l.empty()) throw std::runtime_error("cannot read image '" + lf + "'");
        if (r.empty()) throw std::runtime_error("cannot read image '" + rf + "'");
        if (l.size() != r.size()) throw std::runtime_error("'" + lf + "' and '" + rf + "' differ in size");
        if (size.empty())
            size = l.size();
        else if (l.size() != size)
            throw std::runtime_error("'" + lf + "' is " + std::to_string(l.cols) + "x" + std::to_string(l.rows) +
                                     " but the first image is " + std::to_string(size.width) + "x" +
                                     std::to_string(size.height));
        const bool ok = find_corners(l, o.board, cl) && find_corners(r, o.board, cr);
        if (o.verbose || !ok)
            std::cerr << (ok ? "board found: " : "board not found in both, skipped: ") << lf << " " << rf << "\n";
        if (!ok) continue;
        object.push_back(board_points);
        left_corners.push_back(cl);
        right_corners.push_back(cr);
    }
    if (object.size() < static_cast<std::size_t>(kMinPairs))
        throw std::runtime_error("the board was found in only " + std::to_string(object.size()) + " of " +
                                 std::to_string(pairs.size()) + " pairs; at least " + std::to_string(kMinPairs) +
                                 " are needed");

    // Each camera alone first; the joint refinement then starts from good intrinsics.
    cv::Mat M1, D1, M2, D2, R, T, E, F;
    std::vector<cv::Mat> rv, tv;
    const double rms1 = cv::calibrateCamera(object, left_corners, size, M1, D1, rv, tv);
    const double rms2 = cv::calibrateCamera(object, right_corners, size, M2, D2, rv, tv);
    const double rms = cv::stereoCalibrate(
        object, left_corners, right_corners, M1, D1, M2, D2, size, R, T, E, F, cv::CALIB_USE_INTRINSIC_GUESS,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-6));

    gc::StereoCalibration c;
    c.image_size = size;
    c.M1 = cv::Matx33d(M1);
    c.D1 = D1.reshape(1, 1).clone();
    c.M2 = cv::Matx33d(M2);
    c.D2 = D2.reshape(1, 1).clone();
    c.R = cv::Matx33d(R);
    c.T = cv::Vec3d(T.reshape(1, 3));
    c.has_head_geometry = false;
    c.source = o.out;
    gc::validate_calibration(c);
    const double epipolar = mean_epipolar_error(left_corners, right_corners, c, F);
    gc::save_calibration(c, o.out);

    std::cout << "pairs used: " << object.size() << " of " << pairs.size() << "\n"
              << "image size: " << size.width << "x" << size.height << "\n"
              << "rms reprojection error (left alone, right alone): " << rms1 << " px, " << rms2 << " px\n"
              << "rms reprojection error (stereo): " << rms << " px\n"
              << "mean epipolar error: " << epipolar << " px\n"
              << "baseline: " << cv::norm(c.T) << " mm\n"
              << "written: " << o.out << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    Options options;
    if (const int status = parse(argc, argv, options); status >= 0) return status;
    try {
        return run(options);
    } catch (const UsageError& e) {
        return gc::cli::usage_hint("gesturecam-calibrate", e.what());
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-calibrate: " << e.what() << "\n";
        return 1;
    }
}
