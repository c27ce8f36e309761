// gesturecam-calibrate on OpenCV's stereo chessboard sample pairs (Debian's opencv-doc).
#include "stereo/calibration.hpp"
#include "stereo/extrinsics.hpp"
#include "tools/tool_version.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
const fs::path kData = "/usr/share/doc/opencv-doc/examples/data";

fs::path tool()
{
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    return fs::path(root ? root : ".") / "gst-plugin/tools/gesturecam-calibrate";
}

struct ToolRun {
    int status = -1;
    std::string out;
};

ToolRun run(const std::string& args, const fs::path& log)
{
    const std::string cmd = "'" + tool().string() + "' " + args + " > '" + log.string() + "' 2>&1";
    const int raw = std::system(cmd.c_str());
    ToolRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    r.out = ss.str();
    return r;
}

double printed(const std::string& out, const std::string& label)
{
    std::smatch m;
    if (!std::regex_search(out, m, std::regex(label + ": ([0-9.eE+-]+) px"))) return -1.0;
    return std::stod(m[1]);
}

class Chessboard : public ::testing::Test {
protected:
    void SetUp() override
    {
        ASSERT_TRUE(fs::exists(tool())) << tool();
        ASSERT_TRUE(fs::exists(kData / "left01.jpg"))
            << "opencv-doc's sample images are missing: apt install opencv-doc";
        dir_ = fs::path(::testing::TempDir()) / ("gc_chessboard_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_F(Chessboard, CalibratesTheSamplePairs)
{
    const fs::path out = dir_ / "stereo.yml";
    const ToolRun r =
        run("--left '" + (kData / "left%02d.jpg").string() + "' --right '" + (kData / "right%02d.jpg").string() +
                "' --board 9x6 --square 25 --out '" + out.string() + "'",
            dir_ / "log.txt");
    ASSERT_EQ(r.status, 0) << r.out;
    const double rms = printed(r.out, "rms reprojection error \\(stereo\\)");
    const double epipolar = printed(r.out, "mean epipolar error");
    EXPECT_GT(rms, 0.0) << r.out;
    EXPECT_LT(rms, 1.0) << r.out;
    EXPECT_GT(epipolar, 0.0) << r.out;
    EXPECT_LT(epipolar, 1.0) << r.out;

    const gc::StereoCalibration c = gc::load_calibration(out.string());
    EXPECT_EQ(c.image_size, cv::Size(640, 480));
    EXPECT_FALSE(c.D1.empty());
    EXPECT_GT(cv::norm(c.T), 10.0);
    // The file's geometry, through this product's own F, puts the corners on their lines.
    const cv::Matx33d F = gc::fundamental_matrix(c.M1, c.M2, gc::left_to_right_at(c, {}));
    double sum = 0.0;
    int n = 0;
    for (const char* id : {"01", "03", "06", "12"}) {
        const cv::Mat l = cv::imread((kData / (std::string("left") + id + ".jpg")).string(), cv::IMREAD_GRAYSCALE);
        const cv::Mat rt = cv::imread((kData / (std::string("right") + id + ".jpg")).string(), cv::IMREAD_GRAYSCALE);
        std::vector<cv::Point2f> cl, cr, ul, ur;
        ASSERT_TRUE(cv::findChessboardCorners(l, {9, 6}, cl) && cv::findChessboardCorners(rt, {9, 6}, cr)) << id;
        cv::undistortPoints(cl, ul, c.M1, c.D1, cv::noArray(), c.M1);
        cv::undistortPoints(cr, ur, c.M2, c.D2, cv::noArray(), c.M2);
        for (std::size_t i = 0; i < ul.size(); ++i) {
            const cv::Vec3d line = F * cv::Vec3d(ul[i].x, ul[i].y, 1.0);
            sum += std::abs(line.dot(cv::Vec3d(ur[i].x, ur[i].y, 1.0))) / std::hypot(line[0], line[1]);
            ++n;
        }
    }
    EXPECT_LT(sum / n, 1.0);
}

TEST_F(Chessboard, AcceptsFileLists)
{
    std::string left, right;
    for (const char* id : {"01", "02", "04", "05", "07", "08"}) {
        left += (left.empty() ? "" : ",") + (kData / (std::string("left") + id + ".jpg")).string();
        right += (right.empty() ? "" : ",") + (kData / (std::string("right") + id + ".jpg")).string();
    }
    const fs::path out = dir_ / "stereo.xml";
    const ToolRun r =
        run("--left '" + left + "' --right '" + right + "' --out '" + out.string() + "'", dir_ / "log.txt");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("pairs used: 6 of 6"), std::string::npos) << r.out;
    EXPECT_LT(printed(r.out, "mean epipolar error"), 1.0) << r.out;
    EXPECT_NO_THROW((void)gc::load_calibration(out.string()));
}

TEST_F(Chessboard, OversizedImagesAreRefusedWithTheirSize)
{
    const fs::path wide = dir_ / "wide.png";
    ASSERT_TRUE(cv::imwrite(wide.string(), cv::Mat(40, 8193, CV_8UC1, cv::Scalar(128))));
    const ToolRun r =
        run("--left '" + wide.string() + "' --right '" + wide.string() + "' --out '" + (dir_ / "x.yml").string() + "'",
            dir_ / "log.txt");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.out.find("8193x40"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("8192x8192"), std::string::npos) << r.out;
}

TEST_F(Chessboard, BadArgumentsAreReported)
{
    const std::string l = (kData / "left01.jpg").string(), r = (kData / "right01.jpg").string();
    ToolRun bad = run("--left '" + l + "' --right '" + r + "' --board 9by6", dir_ / "log.txt");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.out.find("--board"), std::string::npos) << bad.out;
    // One line pointing at --help, not the whole usage.
    EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
    EXPECT_NE(bad.out.find("--help"), std::string::npos) << bad.out;
    bad = run("--left '" + l + "' --right '" + r + "," + r + "'", dir_ / "log.txt");
    EXPECT_EQ(bad.status, 2) << bad.out;
    bad = run("--left /nonexistent/a.png --right /nonexistent/b.png --out '" + (dir_ / "x.yml").string() + "'",
              dir_ / "log.txt");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.out.find("/nonexistent/a.png"), std::string::npos) << bad.out;
    bad = run("--left '%s.png' --right '%s.png'", dir_ / "log.txt");
    EXPECT_EQ(bad.status, 2) << bad.out;
    // Too few usable pairs.
    bad = run("--left '" + l + "' --right '" + r + "' --out '" + (dir_ / "x.yml").string() + "'", dir_ / "log.txt");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.out.find("at least"), std::string::npos) << bad.out;
}

TEST_F(Chessboard, AnswersVersionAndHelp)
{
    const ToolRun version = run("--version", dir_ / "log.txt");
    EXPECT_EQ(version.status, 0);
    EXPECT_EQ(version.out, std::string("gesturecam-calibrate ") + GC_TOOL_VERSION + "\n");
    const ToolRun help = run("-h", dir_ / "log.txt");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("--board WxH"), std::string::npos) << help.out;
}

}  // namespace
