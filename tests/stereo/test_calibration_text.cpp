// The strict calibration reader: everything OpenCV's FileStorage writes for a calibration
// reads back exactly, and every construct outside the subset is refused with the line and
// the key in the message.
#include "stereo/calibration.hpp"
#include "stereo/calibration_io.hpp"
#include "stereo/calibration_text.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <utility>

namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class TempDir {
public:
    TempDir() : dir_(fs::path(::testing::TempDir()) / ("gc_calib_text_" + std::to_string(::getpid())))
    {
        fs::create_directories(dir_);
    }
    ~TempDir() { fs::remove_all(dir_); }
    fs::path operator/(const std::string& name) const { return dir_ / name; }

private:
    fs::path dir_;
};

const gc::CalibrationMatrix& matrix(const gc::CalibrationEntries& entries, const std::string& key)
{
    const auto it = entries.find(key);
    if (it == entries.end()) throw std::runtime_error("no key " + key);
    return std::get<gc::CalibrationMatrix>(it->second.value);
}

const gc::CalibrationScalar& scalar(const gc::CalibrationEntries& entries, const std::string& key)
{
    const auto it = entries.find(key);
    if (it == entries.end()) throw std::runtime_error("no key " + key);
    return std::get<gc::CalibrationScalar>(it->second.value);
}

// Same shape and, element by element, the same value as `expected` converted to double
// (NaN matching NaN).
void expect_same(const gc::CalibrationMatrix& m, const cv::Mat& expected, const std::string& key)
{
    ASSERT_EQ(m.rows, expected.rows) << key;
    ASSERT_EQ(m.cols, expected.cols) << key;
    ASSERT_EQ(m.data.size(), expected.total()) << key;
    cv::Mat d;
    expected.convertTo(d, CV_64F);
    for (int i = 0; i < d.rows * d.cols; ++i) {
        const double want = d.at<double>(i / d.cols, i % d.cols);
        if (std::isnan(want)) EXPECT_TRUE(std::isnan(m.data[i])) << key << "[" << i << "]";
        // FileStorage writes a float with the digits of a float, not of the double it widens to.
        else if (expected.depth() == CV_32F)
            EXPECT_EQ(static_cast<float>(m.data[i]), static_cast<float>(want)) << key;
        else
            EXPECT_EQ(m.data[i], want) << key << "[" << i << "]";
    }
}

// Everything a stereoCalibrate user typically writes with FileStorage `<<`.
struct Written {
    cv::Mat M = (cv::Mat_<double>(3, 3) << 554.3, 0, 319.5, 0, 554.3, 239.5, 0, 0, 1);
    cv::Mat big{4, 5, CV_64F};
    cv::Mat ints = (cv::Mat_<int>(2, 2) << 1, -2, 3, 2147483647);
    cv::Mat floats = (cv::Mat_<float>(1, 4) << 1.5f, -1e-30f, NAN, -INFINITY);
    cv::Mat bytes{1, 3, CV_8U, cv::Scalar(7)};
    cv::Mat column = (cv::Mat_<double>(3, 1) << -120.25, 1e-300, 3e300);

    Written() { cv::randu(big, -1000.0, 1000.0); }

    void write(const fs::path& path) const
    {
        cv::FileStorage out(path.string(), cv::FileStorage::WRITE);
        out.writeComment("a comment # with a hash and <markup>");
        out << "count" << 640 << "rms" << 0.25 << "negative" << -3.5e-7 << "empty" << cv::Mat();
        out << "M" << M << "big" << big << "ints" << ints << "floats" << floats << "bytes" << bytes << "column"
            << column;
        out.release();
    }

    void check(const gc::CalibrationEntries& e) const
    {
        EXPECT_EQ(e.size(), 10u);
        EXPECT_EQ(scalar(e, "count").value, 640.0);
        EXPECT_TRUE(scalar(e, "count").integral);
        EXPECT_EQ(scalar(e, "rms").value, 0.25);
        EXPECT_FALSE(scalar(e, "rms").integral);
        EXPECT_EQ(scalar(e, "negative").value, -3.5e-7);
        EXPECT_EQ(matrix(e, "empty").rows, 0);
        EXPECT_TRUE(matrix(e, "empty").data.empty());
        expect_same(matrix(e, "M"), M, "M");
        expect_same(matrix(e, "big"), big, "big");
        expect_same(matrix(e, "ints"), ints, "ints");
        EXPECT_EQ(matrix(e, "ints").dt, 'i');
        expect_same(matrix(e, "floats"), floats, "floats");
        EXPECT_EQ(matrix(e, "floats").dt, 'f');
        expect_same(matrix(e, "bytes"), bytes, "bytes");
        expect_same(matrix(e, "column"), column, "column");
    }
};

TEST(CalibrationText, ReadsWhatFileStorageWritesInYamlAndXml)
{
    const TempDir dir;
    const Written written;
    for (const char* name : {"written.yml", "written.xml"}) {
        SCOPED_TRACE(name);
        written.write(dir / name);
        written.check(gc::read_calibration_text(read_file(dir / name), name));
    }
}

TEST(CalibrationText, AgreesWithFileStorageOnSavedCalibrations)
{
    const TempDir dir;
    gc::StereoCalibration c = gc::default_calibration({640, 480});
    c.D1 = (cv::Mat_<double>(1, 5) << -0.1, 0.01, 1e-4, -2e-4, 0.001);
    c.R = cv::Matx33d(0.9993908270190958, 0, 0.03489949670250097, 0, 1, 0, -0.03489949670250097, 0, 0.9993908270190958);
    c.head.nodal_offset_mm = {0, 0, 15.5};
    for (const char* name : {"saved.yml", "saved.xml"}) {
        SCOPED_TRACE(name);
        gc::save_calibration(c, (dir / name).string());
        const gc::CalibrationEntries e = gc::read_calibration_text(read_file(dir / name), name);
        // The file is our own output here, so OpenCV may read it as the reference.
        cv::FileStorage reference((dir / name).string(), cv::FileStorage::READ);
        ASSERT_TRUE(reference.isOpened());
        int keys = 0;
        for (const cv::FileNode& node : reference.root()) {
            ++keys;
            if (node.isInt()) {
                EXPECT_EQ(scalar(e, node.name()).value, static_cast<int>(node)) << node.name();
            } else {
                cv::Mat m;
                node >> m;
                expect_same(matrix(e, node.name()), m, node.name());
            }
        }
        EXPECT_EQ(keys, 12);
        EXPECT_EQ(e.size(), 12u);
    }
}

// The width and row vector R that both hand-edited files of rig 3 below hold.
void expect_rig_3(const gc::CalibrationEntries& entries)
{
    EXPECT_EQ(scalar(entries, "width").value, 640.0);
    EXPECT_EQ(matrix(entries, "R").data, (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(CalibrationText, AcceptsHandWrittenVariants)
{
    const std::string yaml = "%YAML 1.0\r\n"
                             "# rig 3, measured in the lab\r\n"
                             "---\r\n"
                             "\r\n"
                             "width: 640   # pixels\r\n"
                             "R: !!opencv-matrix   # rotation\r\n"
                             "  dt: d\r\n"
                             "  cols: 3\r\n"
                             "  rows: 1\r\n"
                             "  data: [\r\n"
                             "     1.0,\r\n"
                             "     +2e0 ,3 ]\r\n"
                             "scale: -.5\r\n";
    const gc::CalibrationEntries y = gc::read_calibration_text(yaml, "hand.yml");
    expect_rig_3(y);
    EXPECT_EQ(scalar(y, "scale").value, -0.5);
    EXPECT_EQ(y.at("scale").line, 13u);

    const std::string xml = "<?xml version='1.0' encoding='UTF-8'?>\n"
                            "<!-- rig 3 -->\n"
                            "<opencv_storage>\n"
                            "<width> 640 </width>\n"
                            "<R type_id = 'opencv-matrix'>\n"
                            "  <!-- a row vector -->\n"
                            "  <rows>1</rows> <cols>3</cols>\n"
                            "  <dt>d</dt>\n"
                            "  <data>1.0\n 2e0\t3</data>\n"
                            "</R>\n"
                            "</opencv_storage>\n"
                            "<!-- end -->\n";
    const gc::CalibrationEntries x = gc::read_calibration_text(xml, "hand.xml");
    expect_rig_3(x);
    EXPECT_EQ(x.at("R").line, 5u);
}

// The message names the source, the line and (when given) the key, and says what is wrong.
void expect_refused(const std::string& text, std::size_t line, const std::string& key, const std::string& what)
{
    try {
        (void)gc::read_calibration_text(text, "bad.cal");
        ADD_FAILURE() << "accepted:\n" << text.substr(0, 300);
    } catch (const gc::CalibrationError& err) {
        const std::string msg = err.what();
        EXPECT_NE(msg.find("'bad.cal'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("line " + std::to_string(line) + ":"), std::string::npos) << msg;
        if (!key.empty()) {
            EXPECT_NE(msg.find("key '" + key + "'"), std::string::npos) << msg;
        }
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
    }
}

const std::string kYaml = "%YAML:1.0\n---\n";
const std::string kXml = "<?xml version=\"1.0\"?>\n<opencv_storage>\n";

std::string yaml_matrix(const std::string& key, const std::string& rows, const std::string& cols, const std::string& dt,
                        const std::string& data)
{
    return key + ": !!opencv-matrix\n   rows: " + rows + "\n   cols: " + cols + "\n   dt: " + dt + "\n   data: [ " +
           data + " ]\n";
}

std::string xml_matrix(const std::string& key, const std::string& rows, const std::string& cols, const std::string& dt,
                       const std::string& data)
{
    return "<" + key + " type_id=\"opencv-matrix\">\n  <rows>" + rows + "</rows>\n  <cols>" + cols + "</cols>\n  <dt>" +
           dt + "</dt>\n  <data>\n    " + data + "</data></" + key + ">\n";
}

TEST(CalibrationText, RefusesMatricesOutsideTheLimits)
{
    std::string many;
    for (int i = 0; i < 10001; ++i) many += "1, ";
    many += "1";
    expect_refused(kYaml + "a: 1\n" + yaml_matrix("M", "1", "10002", "d", many), 8, "M", "more than 10000 values");
    expect_refused(kYaml + yaml_matrix("M", "3", "3", "d", "1, 2, 3, 4, 5, 6, 7, 8"), 7, "M", "8 values, expected 9");
    expect_refused(kYaml + yaml_matrix("M", "100000", "100000", "d", "1"), 7, "M", "size 100000x100000");
    expect_refused(kYaml + yaml_matrix("M", "-1", "3", "d", "1"), 4, "M", "rows '-1' is not a non-negative integer");
    expect_refused(kYaml + yaml_matrix("M", "3", "99999999999", "d", "1"), 5, "M", "not a non-negative integer");
    expect_refused(kYaml + yaml_matrix("M", "1", "2", "3d", "1, 2"), 6, "M", "unsupported element type dt '3d'");
    expect_refused(kYaml + yaml_matrix("M", "1", "2", "q", "1, 2"), 6, "M", "unsupported element type");
    expect_refused(kYaml + yaml_matrix("M", "1", "2", "i", "1, 2.5"), 7, "M", "fraction");
    // The data of a 1x2 matrix of doubles, refused on its line (7), and what the message says.
    const std::pair<std::string, std::string> bad_data[] = {
        {"1, abc", "non-number 'abc'"},
        {"1, 0x10", "non-number '0x10'"},
        {"1, 1e999", "non-number"},
        {"1,, 2", "empty value"},
        {"1, 2,", "ends with a ','"},
        {"1 2", "separated by ','"},
        {"1, 2 ] 3", "after the matrix data"},
    };
    for (const auto& [data, what] : bad_data)
        expect_refused(kYaml + yaml_matrix("M", "1", "2", "d", data), 7, "M", what);
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   cols: 1\n   data: [ 1 ]\nb: 2\n", 7, "M",
                   "incomplete matrix");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   rows: 1\n", 5, "M", "'rows' given twice");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   step: 8\n", 5, "M", "unknown matrix field 'step'");

    std::string many_xml;
    for (int i = 0; i < 10002; ++i) many_xml += "1 ";
    expect_refused(kXml + xml_matrix("M", "1", "10002", "d", many_xml) + "</opencv_storage>\n", 8, "M",
                   "more than 10000 values");
    expect_refused(kXml + xml_matrix("M", "2", "2", "d", "1 2 3") + "</opencv_storage>\n", 8, "M",
                   "3 values, expected 4");
    expect_refused(kXml + xml_matrix("M", "1", "2", "dd", "1 2") + "</opencv_storage>\n", 6, "M", "element type");
    expect_refused(kXml + xml_matrix("M", "1", "2", "d", "1 two") + "</opencv_storage>\n", 8, "M", "non-number 'two'");
    expect_refused(kXml + xml_matrix("M", "1", "2", "d", "1, 2") + "</opencv_storage>\n", 8, "M", "non-number '1,'");
}

TEST(CalibrationText, RefusesYamlOutsideTheSubset)
{
    expect_refused("%YAML:1.0\n", 1, "", "no '---'");
    expect_refused("%YAML:1.1\n---\n", 1, "", "expected the header");
    expect_refused("%YAML:1.0\na: 1\n", 2, "", "expected '---'");
    expect_refused(kYaml + "a: 1\nb: 2\na: 3\n", 5, "a", "duplicate key (first given on line 3)");
    expect_refused(kYaml + yaml_matrix("a", "1", "1", "d", "1") + yaml_matrix("a", "1", "1", "d", "1"), 8, "a",
                   "duplicate key");
    expect_refused(kYaml + "a: hello\n", 3, "a", "'hello' is not a number");
    expect_refused(kYaml + "a: '640'\n", 3, "a", "is not a number");
    expect_refused(kYaml + "a: [ 1, 2 ]\n", 3, "a", "is not a number");
    expect_refused(kYaml + "a: { rows: 1 }\n", 3, "a", "is not a number");
    expect_refused(kYaml + "a:\n   b: 1\n", 3, "a", "nested nodes");
    expect_refused(kYaml + "a: 1\n   b: 1\n", 4, "", "outside a matrix");
    expect_refused(kYaml + "- 1\n- 2\n", 3, "", "expected 'name: value'");
    expect_refused(kYaml + "a:1\n", 3, "", "expected 'name: value'");
    expect_refused(kYaml + "M: !!opencv-matrix\n\trows: 1\n", 4, "M", "tab in the indentation");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   cols: 2\n   dt: d\n   data: [ 1,\n", 7, "M",
                   "not closed with ']'");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   cols: 2\n   dt: d\n   data: [ 1,\nb: 2\n", 8, "M",
                   "not closed with ']'");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   cols: 2\n   dt: d\n   data: 1\n", 7, "M", "'[ ... ]'");
    expect_refused(kYaml + "M: !!opencv-matrix\n   rows: 1\n   dt:\n      x: 1\n", 5, "M", "element type");
    expect_refused(kYaml + "a: 1\n" + std::string(gc::kCalibrationMaxLineBytes + 1, ' ') + "\n", 4, "",
                   "longer than 65536 bytes");
}

TEST(CalibrationText, RefusesXmlOutsideTheSubset)
{
    const std::string end = "</opencv_storage>\n";
    expect_refused("<?xml version=\"1.0\"?>\n<storage>\n", 2, "", "expected '<opencv_storage>'");
    expect_refused(kXml + "<a>1</a>\n<b>2</b>\n<a>3</a>\n" + end, 5, "a", "duplicate key (first given on line 3)");
    expect_refused(kXml + "<a>one</a>\n" + end, 3, "a", "'one' is not a number");
    expect_refused(kXml + "<a><b>1</b></a>\n" + end, 3, "a", "is not a number");
    expect_refused(kXml + "<a>1</b>\n" + end, 3, "a", "closing tag </b> does not match <a>");
    expect_refused(kXml + "<a type_id=\"opencv-nd-matrix\"><rows>1</rows></a>\n" + end, 3, "a",
                   "unsupported attribute");
    expect_refused(kXml + "<a type_id=opencv-matrix>\n" + end, 3, "a", "not quoted");
    expect_refused(kXml + "<M type_id=\"opencv-matrix\">\n  <rows>1</rows>\n  <sizes>1</sizes>\n</M>\n" + end, 5, "M",
                   "unknown matrix field 'sizes'");
    expect_refused(kXml + "<M type_id=\"opencv-matrix\">\n  <rows><x>1</x></rows>\n</M>\n" + end, 4, "M",
                   "not a non-negative integer");
    expect_refused(kXml + "<a>1</a>\n", 4, "", "truncated file");
    expect_refused(kXml + "<a>1", 3, "a", "truncated file");
    expect_refused(kXml + "<!-- open\n", 3, "", "comment not closed");
    expect_refused(kXml + "<![CDATA[1]]>\n" + end, 3, "", "expected an element name");
    expect_refused(kXml + end + "<a>1</a>\n", 4, "", "content after </opencv_storage>");
    expect_refused("<?xml version=\"1.0\"?>\n<!DOCTYPE x [<!ENTITY e \"1\">]>\n<opencv_storage>\n" + end, 2, "",
                   "expected '<opencv_storage>'");
}

TEST(CalibrationText, RefusesOtherFormats)
{
    expect_refused("{\"image_width\": 640}", 1, "", "neither YAML");
    expect_refused("image_width: 640\n", 1, "", "neither YAML");
    expect_refused(std::string("\x00\xff<?xml", 7), 1, "", "neither YAML");
    expect_refused("", 1, "", "neither YAML");
}

// Inputs that make a recursive or backtracking parser deep or slow; each must be refused at
// once (a hang shows up as the test's timeout).
TEST(CalibrationText, PathologicalInputsAreRefusedPromptly)
{
    std::string deep_xml = kXml;
    for (int i = 0; i < 200000; ++i) deep_xml += "<a>";
    EXPECT_THROW((void)gc::read_calibration_text(deep_xml, "deep.xml"), gc::CalibrationError);

    std::string open_yaml = kYaml + "M: !!opencv-matrix\n   data: [";
    for (int i = 0; i < 200000; ++i) open_yaml += "[";
    EXPECT_THROW((void)gc::read_calibration_text(open_yaml, "open.yml"), gc::CalibrationError);

    std::string comments = kXml;
    for (int i = 0; i < 100000; ++i) comments += "<!-- -->\n";
    EXPECT_THROW((void)gc::read_calibration_text(comments, "comments.xml"), gc::CalibrationError);

    // Many keys are fine: the reader is linear, not limited in the number of keys.
    std::string many_keys = kYaml;
    for (int i = 0; i < 20000; ++i) {
        const std::string n = std::to_string(i);
        many_keys.append("k").append(n).append(": ").append(n).append("\n");
    }
    EXPECT_EQ(gc::read_calibration_text(many_keys, "many.yml").size(), 20000u);
}

}  // namespace

// Calibration programs often store when they ran as text: read, and ignored by the loader;
// a field given as text is reported as not a number.
TEST(CalibrationText, IgnoresTextValuesSuchAsTheCalibrationTime)
{
    const TempDir dir;
    const gc::StereoCalibration c = gc::default_calibration({640, 480});
    for (const char* name : {"timed.yml", "timed.xml"}) {
        SCOPED_TRACE(name);
        {
            cv::FileStorage out((dir / name).string(), cv::FileStorage::WRITE);
            out << "calibration_time"
                << "Sun Nov 22 04:40:00 2026";
            out << "image_width" << 640 << "image_height" << 480;
            out << "M1" << cv::Mat(c.M1) << "D1" << c.D1 << "M2" << cv::Mat(c.M2) << "D2" << c.D2;
            out << "R" << cv::Mat(c.R) << "T" << cv::Mat(c.T);
        }
        const gc::CalibrationEntries e = gc::read_calibration_text(read_file(dir / name), name);
        ASSERT_EQ(e.count("calibration_time"), 1u);
        EXPECT_EQ(std::get<gc::CalibrationText>(e.at("calibration_time").value).text, "Sun Nov 22 04:40:00 2026");
        EXPECT_EQ(scalar(e, "image_width").value, 640);
        const gc::StereoCalibration loaded = gc::load_calibration((dir / name).string());
        EXPECT_EQ(loaded.image_size, cv::Size(640, 480));
        EXPECT_NEAR(loaded.T[0], c.T[0], 1e-9);
    }
}

TEST(CalibrationText, AFieldGivenAsTextIsNotANumber)
{
    const TempDir dir;
    const fs::path path = dir / "text_width.yml";
    gc::save_calibration(gc::default_calibration({640, 480}), path.string());
    std::string text = read_file(path);
    const auto at = text.find("image_width: 640");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 16, "image_width: \"640\"");
    std::ofstream(path, std::ios::binary) << text;
    try {
        gc::load_calibration(path.string());
        FAIL() << "a text image_width was accepted";
    } catch (const gc::CalibrationError& e) {
        EXPECT_NE(std::string(e.what()).find("image_width"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("not an integer"), std::string::npos) << e.what();
    }
}
