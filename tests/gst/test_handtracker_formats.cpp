// handtracker reads every listed input format and writes every output format without a
// videoconvert, as videoconvert would (colorimetry, range, padded strides of odd widths);
// mismatched views fail in words.
#include "gst_fixture.hpp"

#include <glib/gstdio.h>
#include <gst/video/video.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <string>

namespace {

using gc::test::drain;
using gc::test::run_pipeline;

// 322x242: packed rows and chroma planes of this width need padding to 4-byte strides.
constexpr const char* kSize = "width=322,height=242,framerate=30/1";

cv::Mat bgr_of(GstSample* sample)
{
    GstVideoInfo info;
    EXPECT_TRUE(gst_video_info_from_caps(&info, gst_sample_get_caps(sample)));
    GstVideoFrame frame;
    EXPECT_TRUE(gst_video_frame_map(&frame, &info, gst_sample_get_buffer(sample), GST_MAP_READ));
    cv::Mat header(info.height, info.width, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                   size_t(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
    cv::Mat copy = header.clone();
    gst_video_frame_unmap(&frame);
    return copy;
}

// Runs `branch` and `reference` (from a tee of the test source) side by side and returns the
// largest difference, in grey levels, between their BGR results.
int difference(const std::string& source_caps, const std::string& branch, const std::string& reference)
{
    const std::string description = "videotestsrc num-buffers=2 pattern=smpte ! " + source_caps +
                                    " ! tee name=s "
                                    "s. ! queue ! " +
                                    branch +
                                    " ! video/x-raw,format=BGR ! appsink name=out sync=false wait-on-eos=false "
                                    "s. ! queue ! " +
                                    reference +
                                    " ! video/x-raw,format=BGR ! appsink name=ref sync=false wait-on-eos=false";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(description);
    if (!pipeline) return 1000;
    std::vector<gc::test::SamplePtr> out, ref;
    const gc::test::RunResult r = run_pipeline(pipeline.get(), 30 * GST_SECOND, [&] {
        out = drain(pipeline.get(), "out");
        ref = drain(pipeline.get(), "ref");
    });
    EXPECT_TRUE(r.eos) << r.error;
    EXPECT_EQ(out.size(), 2u);
    EXPECT_EQ(ref.size(), 2u);
    double worst = 0.0;
    for (size_t i = 0; i < std::min(out.size(), ref.size()); ++i) {
        const cv::Mat a = bgr_of(out[i].get());
        const cv::Mat b = bgr_of(ref[i].get());
        EXPECT_EQ(a.size(), b.size());
        if (a.size() != b.size()) return 1000;
        worst = std::max(worst, cv::norm(a, b, cv::NORM_INF));
    }
    return int(worst);
}

// The picture the tracker sees is the one videoconvert would give, to within one grey level.
int input_difference(const std::string& source_caps)
{
    return difference(source_caps, "handtracker output=left", "videoconvert");
}

class InputFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(InputFormat, MatchesVideoconvert)
{
    gc::test::init_gstreamer();
    EXPECT_LE(input_difference(std::string("video/x-raw,format=") + GetParam() + "," + kSize), 1) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Handtracker, InputFormat,
                         ::testing::Values("YUY2", "NV12", "I420", "RGB", "BGR", "RGBx", "BGRx", "xRGB", "xBGR", "RGBA",
                                           "BGRA"));

// HD cameras send BT.709, webcams' MJPEG full-range BT.601 ("1:4:0:0"): each is read as its
// caps say, not as limited-range BT.601 always.
class InputColorimetry : public ::testing::TestWithParam<const char*> {};

TEST_P(InputColorimetry, MatchesVideoconvert)
{
    gc::test::init_gstreamer();
    for (const char* format : {"I420", "NV12", "YUY2"}) {
        const std::string caps =
            std::string("video/x-raw,format=") + format + ",colorimetry=" + GetParam() + "," + kSize;
        EXPECT_LE(input_difference(caps), 1) << format << " " << GetParam();
    }
}

INSTANTIATE_TEST_SUITE_P(Handtracker, InputColorimetry, ::testing::Values("bt601", "bt709", "1:4:0:0", "1:3:5:1"));

// Written in any output format, the picture is what videoconvert would write from the same
// BGR picture, to within one grey level once read back.
class OutputFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(OutputFormat, MatchesVideoconvert)
{
    gc::test::init_gstreamer();
    const std::string format = std::string("video/x-raw,format=") + GetParam();
    EXPECT_LE(difference(std::string("video/x-raw,format=BGR,") + kSize,
                         "handtracker output=left ! " + format + " ! videoconvert",
                         "videoconvert ! " + format + " ! videoconvert"),
              1)
        << GetParam();
    const bool yuv = std::string(GetParam()) == "I420" || std::string(GetParam()) == "NV12";
    if (yuv) {
        EXPECT_LE(difference(std::string("video/x-raw,format=BGR,") + kSize,
                             "handtracker output=left ! " + format + ",colorimetry=bt709 ! videoconvert",
                             "videoconvert ! " + format + ",colorimetry=bt709 ! videoconvert"),
                  1)
            << GetParam() << " bt709";
    }
}

INSTANTIATE_TEST_SUITE_P(Handtracker, OutputFormat,
                         ::testing::Values("BGR", "RGB", "BGRx", "RGBx", "xRGB", "xBGR", "BGRA", "RGBA", "I420",
                                           "NV12"));

struct Track {
    std::string state;
    double fingertip_x = 0.0, fingertip_y = 0.0;
};

// The left eye's state and fingertip on each frame of the rendered scene, delivered in `caps`.
std::vector<Track> track_scene(const std::string& caps)
{
    const std::string eye = " scene=clean motion=mixed num-buffers=90 ! " + caps + " ! ";
    const gc::test::RunResult r = run_pipeline("handscenesrc eye=left" + eye + "t.sink_left handscenesrc eye=right" +
                                                   eye + "t.sink_right handtracker name=t ! fakesink sync=false",
                                               120 * GST_SECOND);
    EXPECT_TRUE(r.eos) << r.error;
    std::vector<Track> out;
    for (const GstStructure* msg : r.named("hand-pointing", "t")) {
        Track t;
        t.state = gst_structure_get_string(msg, "state");
        if (const GstStructure* left = gc::test::get_child(msg, "left")) {
            t.fingertip_x = gc::test::get_double(left, "fingertip-x");
            t.fingertip_y = gc::test::get_double(left, "fingertip-y");
        }
        out.push_back(t);
    }
    return out;
}

// The same scene delivered as RGB and as BT.709 I420 (an HD camera's format) is tracked alike:
// the same state on every frame but one, the fingertips a median 2.5 px apart at most (each
// run learns its skin and remakes its template from its own colours, which the chroma
// subsampling moves a little).
TEST(Colorimetry, Bt709TracksLikeRgb)
{
    gc::test::init_gstreamer();
    const std::vector<Track> rgb = track_scene("video/x-raw,format=RGB");
    const std::vector<Track> yuv = track_scene("video/x-raw,format=I420,colorimetry=bt709");
    ASSERT_EQ(rgb.size(), 90u);
    ASSERT_EQ(yuv.size(), rgb.size());
    int same_state = 0;
    std::vector<double> apart;
    for (size_t i = 0; i < rgb.size(); ++i) {
        same_state += rgb[i].state == yuv[i].state;
        if (rgb[i].state == "tracking" && yuv[i].state == "tracking")
            apart.push_back(
                std::hypot(rgb[i].fingertip_x - yuv[i].fingertip_x, rgb[i].fingertip_y - yuv[i].fingertip_y));
    }
    EXPECT_GE(same_state, 89) << "of 90 frames";
    ASSERT_GE(apart.size(), 60u);
    std::nth_element(apart.begin(), apart.begin() + long(apart.size() / 2), apart.end());
    EXPECT_LE(apart[apart.size() / 2], 2.5);
}

TEST(Negotiation, MismatchedViewsFailWithBothSizes)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r =
        run_pipeline("videotestsrc num-buffers=5 ! video/x-raw,format=BGR,width=640,height=480 ! t.sink_left "
                     "videotestsrc num-buffers=5 ! video/x-raw,format=BGR,width=320,height=240 ! t.sink_right "
                     "handtracker name=t ! fakesink",
                     20 * GST_SECOND);
    EXPECT_FALSE(r.eos);
    EXPECT_NE(r.error.find("sink_left is 640x480 but sink_right is 320x240"), std::string::npos) << r.error;
}

// A decoder learns the frame size from the stream, so the refusal comes at run time and
// names the size.
TEST(Negotiation, FramesOverTheSizeLimitAreRefusedWithTheirSize)
{
    gc::test::init_gstreamer();
    const std::string dir = g_get_tmp_dir();
    const std::string wide = dir + "/gesturecam-wide-" + std::to_string(::getpid()) + ".png";
    const std::string largest = dir + "/gesturecam-largest-" + std::to_string(::getpid()) + ".png";
    ASSERT_TRUE(cv::imwrite(wide, cv::Mat(32, 8193, CV_8UC3, cv::Scalar(40, 90, 160))));
    ASSERT_TRUE(cv::imwrite(largest, cv::Mat(32, 8192, CV_8UC3, cv::Scalar(40, 90, 160))));
    const auto decoded = [](const std::string& png) {
        return run_pipeline("filesrc location=" + png +
                                " ! pngdec ! t.sink_left handtracker name=t particles=50 ! "
                                "fakesink",
                            20 * GST_SECOND);
    };
    const gc::test::RunResult refused = decoded(wide);
    EXPECT_FALSE(refused.eos);
    const bool named = std::any_of(refused.warnings.begin(), refused.warnings.end(), [](const std::string& w) {
        return w.find("8193x32") != std::string::npos && w.find("8192x8192") != std::string::npos;
    });
    EXPECT_TRUE(named) << refused.warnings.size() << " warnings; error: " << refused.error;
    const gc::test::RunResult accepted = decoded(largest);
    EXPECT_TRUE(accepted.eos) << accepted.error;
    g_remove(wide.c_str());
    g_remove(largest.c_str());
}

TEST(Negotiation, DownstreamChoosesTheOutputSize)
{
    gc::test::init_gstreamer();
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "videotestsrc num-buffers=6 ! video/x-raw,format=BGR,width=160,height=120 ! t.sink_left "
        "videotestsrc num-buffers=6 ! video/x-raw,format=BGR,width=160,height=120 ! t.sink_right "
        "handtracker name=t output=attended ! video/x-raw,width=96,height=64 ! appsink name=out sync=false "
        "wait-on-eos=false");
    ASSERT_TRUE(pipeline);
    std::vector<gc::test::SamplePtr> out;
    const gc::test::RunResult r =
        run_pipeline(pipeline.get(), 20 * GST_SECOND, [&] { out = drain(pipeline.get(), "out"); });
    EXPECT_TRUE(r.eos) << r.error;
    EXPECT_EQ(r.named("hand-pointing").size(), 6u);
    ASSERT_EQ(out.size(), 6u);
    GstVideoInfo info;
    ASSERT_TRUE(gst_video_info_from_caps(&info, gst_sample_get_caps(out[0].get())));
    EXPECT_EQ(info.width, 96);
    EXPECT_EQ(info.height, 64);
}

}  // namespace
