// The calibration file: loading in both formats, every malformed case with a message that
// names the key and the file, saving, and the nominal default.
#include "stereo/calibration.hpp"
#include "stereo/calibration_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

// A matrix entry as text, so each case can corrupt exactly one thing.
struct Entry {
    int rows = 0, cols = 0;  // 0x0: a scalar
    std::string data;        // space-separated values (or the scalar)
    std::string dt = "d";
};

using Entries = std::map<std::string, Entry>;

Entries valid_entries()
{
    return {
        {"image_width", {0, 0, "640"}},
        {"image_height", {0, 0, "480"}},
        {"M1", {3, 3, "554.3 0 319.5 0 554.3 239.5 0 0 1"}},
        {"D1", {1, 5, "-0.1 0.01 0 0 0"}},
        {"M2", {3, 3, "550 0 320 0 551 240 0 0 1"}},
        {"D2", {1, 5, "-0.12 0.02 0 0 0"}},
        // 2 degrees about y, written to 7 digits as a hand-edited file would be.
        {"R", {3, 3, "0.9993908 0 0.0348995 0 1 0 -0.0348995 0 0.9993908"}},
        {"T", {3, 1, "-120.5 0.3 1.2"}},
    };
}

std::string yaml(const Entries& entries)
{
    std::string s = "%YAML:1.0\n---\n";
    for (const auto& [key, e] : entries) {
        if (e.rows == 0 && e.cols == 0) {
            s += key + ": " + e.data + "\n";
            continue;
        }
        std::string data = e.data;
        for (std::size_t p = data.find(' '); p != std::string::npos; p = data.find(' ', p + 2))
            data.replace(p, 1, ", ");
        s += key + ": !!opencv-matrix\n   rows: " + std::to_string(e.rows) + "\n   cols: " + std::to_string(e.cols) +
             "\n   dt: " + e.dt + "\n   data: [ " + data + " ]\n";
    }
    return s;
}

std::string xml(const Entries& entries)
{
    std::string s = "<?xml version=\"1.0\"?>\n<opencv_storage>\n";
    for (const auto& [key, e] : entries) {
        if (e.rows == 0 && e.cols == 0) {
            s += "<" + key + ">" + e.data + "</" + key + ">\n";
            continue;
        }
        s += "<" + key + " type_id=\"opencv-matrix\">\n  <rows>" + std::to_string(e.rows) + "</rows>\n  <cols>" +
             std::to_string(e.cols) + "</cols>\n  <dt>" + e.dt + "</dt>\n  <data>\n    " + e.data + "</data></" + key +
             ">\n";
    }
    return s + "</opencv_storage>\n";
}

class CalibrationFile : public ::testing::TestWithParam<bool> {  // param: XML?
protected:
    void SetUp() override
    {
        dir_ = fs::path(::testing::TempDir()) / ("gc_calib_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    bool is_xml() const { return GetParam(); }
    std::string write(const std::string& name, const std::string& text)
    {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }
    std::string write(const Entries& e)
    {
        return write(is_xml() ? "calib.xml" : "calib.yml", is_xml() ? xml(e) : yaml(e));
    }

    // Loading must fail with a message naming `key` and the file.
    void expect_error(const Entries& e, const std::string& key, const std::string& what = "")
    {
        const std::string path = write(e);
        try {
            (void)gc::load_calibration(path);
            ADD_FAILURE() << "no error for a bad '" << key << "'";
        } catch (const gc::CalibrationError& err) {
            const std::string msg = err.what();
            EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << msg;
            EXPECT_NE(msg.find(path), std::string::npos) << msg;
            if (!what.empty()) {
                EXPECT_NE(msg.find(what), std::string::npos) << msg;
            }
        }
    }

    fs::path dir_;
};

TEST_P(CalibrationFile, LoadsAValidFile)
{
    const std::string path = write(valid_entries());
    const gc::StereoCalibration c = gc::load_calibration(path);
    EXPECT_EQ(c.image_size, cv::Size(640, 480));
    EXPECT_DOUBLE_EQ(c.M1(0, 0), 554.3);
    EXPECT_DOUBLE_EQ(c.M2(1, 2), 240.0);
    EXPECT_EQ(c.D1.total(), 5u);
    EXPECT_DOUBLE_EQ(c.D2.at<double>(0, 1), 0.02);
    EXPECT_NEAR(c.R(0, 2), 0.0348995, 1e-12);
    EXPECT_EQ(c.T, cv::Vec3d(-120.5, 0.3, 1.2));
    EXPECT_EQ(c.source, path);
    // No head keys: the geometry comes from the baseline.
    EXPECT_FALSE(c.has_head_geometry);
    EXPECT_NEAR(c.head.baseline_mm(), cv::norm(c.T), 1e-9);
    EXPECT_NEAR(c.head.left_eye_mm[0], -0.5 * cv::norm(c.T), 1e-9);
}

TEST_P(CalibrationFile, ReadsHeadGeometryAndVectorsStoredAsRows)
{
    Entries e = valid_entries();
    e["T"] = {1, 3, "-120 0 0"};
    e["head_left_eye"] = {3, 1, "-61 0 0"};
    e["head_right_eye"] = {3, 1, "59 0 0"};
    e["head_tilt_centre"] = {3, 1, "0 -40 10"};
    e["head_nodal_offset"] = {1, 3, "0 0 15"};
    const gc::StereoCalibration c = gc::load_calibration(write(e));
    EXPECT_TRUE(c.has_head_geometry);
    EXPECT_EQ(c.T, cv::Vec3d(-120, 0, 0));
    EXPECT_EQ(c.head.left_eye_mm, cv::Vec3d(-61, 0, 0));
    EXPECT_EQ(c.head.tilt_centre_mm, cv::Vec3d(0, -40, 10));
    EXPECT_EQ(c.head.nodal_offset_mm, cv::Vec3d(0, 0, 15));
}

TEST_P(CalibrationFile, EveryMissingRequiredKeyIsNamed)
{
    for (const char* key : {"image_width", "image_height", "M1", "D1", "M2", "D2", "R", "T"}) {
        Entries e = valid_entries();
        e.erase(key);
        expect_error(e, key, "missing");
    }
}

TEST_P(CalibrationFile, PartialHeadGeometryIsNamed)
{
    Entries e = valid_entries();
    e["head_left_eye"] = {3, 1, "-60 0 0"};
    e["head_right_eye"] = {3, 1, "60 0 0"};
    e["head_tilt_centre"] = {3, 1, "0 0 0"};
    expect_error(e, "head_nodal_offset", "missing");
}

Entries with_director(Entries e)
{
    e["director_image_width"] = {0, 0, "1920"};
    e["director_image_height"] = {0, 0, "1080"};
    e["director_M"] = {3, 3, "1662.8 0 959.5 0 1662.8 539.5 0 0 1"};
    // Turned 30 degrees to the left, standing 750 mm to the right of the head and 1.3 m ahead.
    e["director_R"] = {3, 3, "0.8660254 0 0.5 0 1 0 -0.5 0 0.8660254"};
    e["director_T"] = {3, 1, "-1299 0 -750"};
    return e;
}

TEST_P(CalibrationFile, ReadsTheDirectorCamera)
{
    EXPECT_FALSE(gc::load_calibration(write(valid_entries())).director);
    const gc::StereoCalibration c = gc::load_calibration(write(with_director(valid_entries())));
    ASSERT_TRUE(c.director);
    EXPECT_EQ(c.director->image_size, cv::Size(1920, 1080));
    EXPECT_DOUBLE_EQ(c.director->K(0, 0), 1662.8);
    EXPECT_DOUBLE_EQ(c.director->head_to_base.R(0, 2), 0.5);
    EXPECT_EQ(c.director->head_to_base.t, cv::Vec3d(-1299, 0, -750));
}

TEST_P(CalibrationFile, BadDirectorKeysAreNamed)
{
    for (const char* key :
         {"director_image_width", "director_image_height", "director_M", "director_R", "director_T"}) {
        Entries e = with_director(valid_entries());
        e.erase(key);
        expect_error(e, key, "missing (the director keys come all together or not at all)");
    }
    Entries e = with_director(valid_entries());
    e["director_R"] = {3, 3, "1 0 0 0 1 0 0 0 2"};
    expect_error(e, "director_R", "not a rotation matrix");
    e = with_director(valid_entries());
    e["director_M"] = {3, 3, "1662.8 0 2500 0 1662.8 539.5 0 0 1"};
    expect_error(e, "director_M", "principal point cx");
    e = with_director(valid_entries());
    e["director_T"] = {3, 1, "-1299 0 1e9"};
    expect_error(e, "director_T", "|director_T|");
    e = with_director(valid_entries());
    e["director_T"] = {3, 1, "-1299 .nan 0"};
    expect_error(e, "director_T");
}

TEST_P(CalibrationFile, WrongShapesAreNamed)
{
    const std::map<std::string, Entry> bad{
        {"M1", {2, 3, "554 0 320 0 554 240"}},
        {"M2", {3, 1, "1 2 3"}},
        {"R", {2, 2, "1 0 0 1"}},
        {"T", {2, 1, "-120 0"}},
        {"D1", {1, 3, "0 0 0"}},
        {"D2", {2, 5, "0 0 0 0 0 0 0 0 0 0"}},
    };
    for (const auto& [key, entry] : bad) {
        Entries e = valid_entries();
        e[key] = entry;
        expect_error(e, key, "shape");
    }
    Entries e = valid_entries();
    e["head_left_eye"] = {3, 1, "-60 0 0"};
    e["head_right_eye"] = {2, 1, "60 0"};
    e["head_tilt_centre"] = {3, 1, "0 0 0"};
    e["head_nodal_offset"] = {3, 1, "0 0 0"};
    expect_error(e, "head_right_eye", "shape");
}

TEST_P(CalibrationFile, DataCountNotMatchingTheShapeIsNamed)
{
    Entries e = valid_entries();
    e["M2"] = {3, 3, "550 0 320 0 551 240 0 0"};
    expect_error(e, "M2", "8 values");
}

TEST_P(CalibrationFile, NonFiniteValuesAreNamed)
{
    for (const std::string key : {"M1", "D1", "R", "T"}) {
        for (const std::string bad : {".nan", ".inf", "-.inf"}) {
            Entries e = valid_entries();
            const std::size_t first_space = e[key].data.find(' ');
            e[key].data = bad + e[key].data.substr(first_space);
            expect_error(e, key);
        }
    }
}

TEST_P(CalibrationFile, RotationThatIsNotOneIsNamed)
{
    Entries scaled = valid_entries();
    scaled["R"].data = "2 0 0 0 2 0 0 0 2";
    expect_error(scaled, "R", "not a rotation");
    Entries mirror = valid_entries();
    mirror["R"].data = "-1 0 0 0 1 0 0 0 1";  // orthogonal, det = -1
    expect_error(mirror, "R", "not a rotation");
    Entries sheared = valid_entries();
    sheared["R"].data = "1 0.01 0 0 1 0 0 0 1";
    expect_error(sheared, "R", "not a rotation");
}

TEST_P(CalibrationFile, ImplausibleValuesAreNamed)
{
    Entries width = valid_entries();
    width["image_width"].data = "0";
    expect_error(width, "image_width", "out of range");
    Entries height = valid_entries();
    height["image_height"].data = "480.5";
    expect_error(height, "image_height", "integer");
    Entries focal = valid_entries();
    focal["M1"].data = "-554 0 320 0 554 240 0 0 1";
    expect_error(focal, "M1", "focal");
    Entries bottom = valid_entries();
    bottom["M2"].data = "550 0 320 0 551 240 0 0 2";
    expect_error(bottom, "M2");
    Entries baseline = valid_entries();
    baseline["T"].data = "0 0 0";
    expect_error(baseline, "T", "baseline");
    Entries huge = valid_entries();
    huge["R"] = {100000, 100000, "1"};
    expect_error(huge, "R", "size");
    Entries type = valid_entries();
    type["R"].dt = "dd";
    expect_error(type, "R", "type");
    Entries scalar = valid_entries();
    scalar["M1"] = {0, 0, "554"};
    expect_error(scalar, "M1", "not a matrix");
}

TEST_P(CalibrationFile, PhysicallyAbsurdValuesAreNamed)
{
    // Each value is finite and parses, yet no camera has it; each names its key and quantity.
    const struct {
        const char* key;
        const char* data;
        const char* what;
    } cases[] = {
        {"M1", "1e-300 0 319.5 0 554.3 239.5 0 0 1", "fx"},
        {"M1", "1e11 0 319.5 0 554.3 239.5 0 0 1", "fx"},
        {"M2", "550 0 320 0 1e11 240 0 0 1", "fy"},
        {"M1", "554.3 0 -1e9 0 554.3 239.5 0 0 1", "cx"},
        {"M2", "550 0 320 0 551 4800 0 0 1", "cy"},
        {"T", "1e11 0 0", "baseline"},
        {"T", "-5 0 0", "baseline"},
        {"D1", "1e11 0.01 0 0 0", "coefficient 1"},
        {"D2", "-0.12 0.02 0 0 -500", "coefficient 5"},
    };
    for (const auto& c : cases) {
        Entries e = valid_entries();
        e[c.key].data = c.data;
        expect_error(e, c.key, c.what);
    }
}

TEST_P(CalibrationFile, TruncatedFilesFailCleanly)
{
    const std::string full = is_xml() ? xml(valid_entries()) : yaml(valid_entries());
    int failures = 0;
    // Every cut before the last key is complete must fail; none may crash or load garbage.
    for (std::size_t cut = 1; cut + 40 < full.size(); cut += 7) {
        const std::string path = write(is_xml() ? "cut.xml" : "cut.yml", full.substr(0, cut));
        try {
            (void)gc::load_calibration(path);
            ADD_FAILURE() << "loaded a file cut at byte " << cut << " of " << full.size();
        } catch (const gc::CalibrationError& err) {
            EXPECT_NE(std::string(err.what()).find(path), std::string::npos) << err.what();
            ++failures;
        }
    }
    EXPECT_GT(failures, 20);
}

TEST_P(CalibrationFile, SyntaxErrorsNameTheFile)
{
    const std::string path = write(is_xml() ? "bad.xml" : "bad.yml",
                                   is_xml() ? "<?xml version=\"1.0\"?>\n<opencv_storage>\n<M1><rows>3</cols>\n"
                                            : "%YAML:1.0\n---\nM1: !!opencv-matrix\n   rows: [3\n  cols: }\n");
    try {
        (void)gc::load_calibration(path);
        ADD_FAILURE() << "no error";
    } catch (const gc::CalibrationError& err) {
        EXPECT_NE(std::string(err.what()).find(path), std::string::npos) << err.what();
    }
}

TEST_P(CalibrationFile, SaveThenLoadRoundTrips)
{
    gc::StereoCalibration c = gc::default_calibration({800, 600});
    c.D1 = (cv::Mat_<double>(1, 5) << -0.2, 0.05, 0.001, -0.002, 0.01);
    c.R = cv::Matx33d(0.99939082701909576, 0.0, 0.034899496702500969, 0.0, 1.0, 0.0, -0.034899496702500969, 0.0,
                      0.99939082701909576);
    c.T = {-119.0, 0.5, -2.0};
    c.head.tilt_centre_mm = {0.0, -35.0, 12.0};
    c.head.nodal_offset_mm = {0.0, 0.0, 18.0};
    const std::string path = (dir_ / (is_xml() ? "saved.xml" : "saved.yml")).string();
    gc::save_calibration(c, path);
    const gc::StereoCalibration back = gc::load_calibration(path);
    EXPECT_EQ(back.image_size, c.image_size);
    EXPECT_LT(cv::norm(back.M1, c.M1, cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(back.M2, c.M2, cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(back.D1, c.D1, cv::NORM_INF), 1e-15);
    EXPECT_LT(cv::norm(back.D2, cv::NORM_INF), 1e-15);  // no distortion saved as zeros
    EXPECT_LT(cv::norm(back.R, c.R, cv::NORM_INF), 1e-15);
    EXPECT_LT(cv::norm(back.T, c.T, cv::NORM_INF), 1e-12);
    EXPECT_TRUE(back.has_head_geometry);
    EXPECT_EQ(back.head.tilt_centre_mm, c.head.tilt_centre_mm);
    EXPECT_EQ(back.head.nodal_offset_mm, c.head.nodal_offset_mm);
    EXPECT_EQ(back.head.right_eye_mm, c.head.right_eye_mm);
    EXPECT_FALSE(back.director);

    gc::DirectorMount director;
    director.head_to_base = {gc::rotation_about_y(-25.0), {800.0, -300.0, 100.0}};
    c.director = director;
    gc::save_calibration(c, path);
    const gc::StereoCalibration with = gc::load_calibration(path);
    ASSERT_TRUE(with.director);
    EXPECT_EQ(with.director->image_size, director.image_size);
    EXPECT_LT(cv::norm(with.director->K, director.K, cv::NORM_INF), 1e-12);
    EXPECT_LT(cv::norm(with.director->head_to_base.R, director.head_to_base.R, cv::NORM_INF), 1e-15);
    EXPECT_LT(cv::norm(with.director->head_to_base.t, director.head_to_base.t, cv::NORM_INF), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Formats, CalibrationFile, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) { return info.param ? "Xml" : "Yaml"; });

TEST(Calibration, MissingFileIsNamed)
{
    const std::string path = "/nonexistent/dir/calibration.yml";
    try {
        (void)gc::load_calibration(path);
        ADD_FAILURE() << "no error";
    } catch (const gc::CalibrationError& err) {
        EXPECT_NE(std::string(err.what()).find(path), std::string::npos) << err.what();
    }
}

// Loading must fail at once with a CalibrationError naming `path` and saying `what`.
void expect_refused(const std::string& path, const std::string& what)
{
    try {
        (void)gc::load_calibration(path);
        ADD_FAILURE() << "no error for " << path;
    } catch (const gc::CalibrationError& err) {
        const std::string msg = err.what();
        EXPECT_NE(msg.find("'" + path + "'"), std::string::npos) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
    }
}

TEST(Calibration, OnlySmallRegularFilesAreRead)
{
    const fs::path dir = fs::path(::testing::TempDir()) / ("gc_calib_kinds_" + std::to_string(::getpid()));
    fs::create_directories(dir / "rig.yml");
    expect_refused((dir / "rig.yml").string(), "directory");
    // A FIFO without a writer: opening it for reading would wait for one forever.
    const fs::path fifo = dir / "fifo.yml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expect_refused(fifo.string(), "FIFO");
    expect_refused("/dev/zero", "character device");

    // A valid calibration followed by unknown keys: read below 1 MiB, refused above it.
    std::string text = yaml(valid_entries());
    for (int i = 0; text.size() < 1000000; ++i) text += "unknown_" + std::to_string(i) + ": 1\n";
    const fs::path below = dir / "below.yml";
    std::ofstream(below, std::ios::binary) << text;
    EXPECT_NO_THROW((void)gc::load_calibration(below.string()));
    for (int i = 0; text.size() < 2000000; ++i) text += "more_" + std::to_string(i) + ": 1\n";
    const fs::path above = dir / "above.yml";
    std::ofstream(above, std::ios::binary) << text;
    expect_refused(above.string(), "limit");
    fs::remove_all(dir);
}

TEST(Calibration, EmptyAndBinaryContentFailCleanly)
{
    EXPECT_THROW((void)gc::parse_calibration("", "empty.yml"), gc::CalibrationError);
    EXPECT_THROW((void)gc::parse_calibration(std::string("\x00\xff\x7f<?", 5), "bin.yml"), gc::CalibrationError);
    EXPECT_THROW((void)gc::parse_calibration("{\"image_width\": 640}", "c.json"), gc::CalibrationError);
    EXPECT_THROW((void)gc::parse_calibration("%YAML:1.0\n---\n- 1\n- 2\n", "seq.yml"), gc::CalibrationError);
}

TEST(Calibration, SizeMismatchNamesBothSizes)
{
    const gc::StereoCalibration c = gc::default_calibration({640, 480});
    EXPECT_NO_THROW(gc::validate_calibration_size(c, {640, 480}));
    try {
        gc::validate_calibration_size(c, {1280, 720});
        ADD_FAILURE() << "no error";
    } catch (const gc::CalibrationError& err) {
        const std::string msg = err.what();
        EXPECT_NE(msg.find("640x480"), std::string::npos) << msg;
        EXPECT_NE(msg.find("1280x720"), std::string::npos) << msg;
        EXPECT_NE(msg.find("default"), std::string::npos) << msg;
    }
}

TEST(Calibration, DefaultIsTheNominalRig)
{
    const gc::StereoCalibration c = gc::default_calibration({640, 480});
    const double hfov = 2.0 * std::atan(320.0 / c.M1(0, 0)) * 180.0 / std::numbers::pi;
    EXPECT_NEAR(hfov, 60.0, 1e-9);
    EXPECT_EQ(c.M1, c.M2);
    EXPECT_DOUBLE_EQ(c.M1(0, 0), c.M1(1, 1));
    EXPECT_DOUBLE_EQ(c.M1(0, 2), 319.5);
    EXPECT_DOUBLE_EQ(c.M1(1, 2), 239.5);
    EXPECT_TRUE(c.D1.empty());
    EXPECT_TRUE(c.D2.empty());
    EXPECT_EQ(c.R, cv::Matx33d::eye());
    EXPECT_EQ(c.T, cv::Vec3d(-120, 0, 0));
    EXPECT_TRUE(c.has_head_geometry);
    EXPECT_EQ(c.head.left_eye_mm, cv::Vec3d(-60, 0, 0));
    EXPECT_EQ(c.head.right_eye_mm, cv::Vec3d(60, 0, 0));
    EXPECT_NO_THROW(gc::validate_calibration(c));
    EXPECT_THROW((void)gc::default_calibration({0, 480}), gc::CalibrationError);
}

TEST(Calibration, SavingAnInvalidCalibrationIsRefused)
{
    gc::StereoCalibration c = gc::default_calibration({640, 480});
    c.R = cv::Matx33d(1, 0, 0, 0, 1, 0, 0, 0, 3);
    EXPECT_THROW(gc::save_calibration(c, ::testing::TempDir() + "/never.yml"), gc::CalibrationError);
    c = gc::default_calibration({640, 480});
    EXPECT_THROW(gc::save_calibration(c, "/nonexistent/dir/calibration.yml"), gc::CalibrationError);
}

}  // namespace
