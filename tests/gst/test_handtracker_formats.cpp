// handtracker reads every listed input format and writes every output format itself, with
// padded strides (odd widths), without a videoconvert; mismatched views fail in words.
#include "gst_fixture.hpp"

#include <glib/gstdio.h>
#include <gst/video/video.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include <algorithm>
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

// Runs `branch` (from a tee of the test source) next to videoconvert's reference and
// returns the largest mean absolute difference between the two BGR results.
double difference_to_reference(const std::string& source_caps, const std::string& branch)
{
    const std::string description =
        "videotestsrc num-buffers=2 pattern=smpte ! " + source_caps + " ! tee name=s "
        "s. ! queue ! " + branch + " ! video/x-raw,format=BGR ! appsink name=out sync=false wait-on-eos=false "
        "s. ! queue ! videoconvert ! video/x-raw,format=BGR ! appsink name=ref sync=false wait-on-eos=false";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(description);
    if (!pipeline)
        return 1e9;
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
        if (a.size() != b.size())
            return 1e9;
        const cv::Scalar mean = cv::mean(cv::abs(a - b) + cv::abs(b - a));
        worst = std::max({worst, mean[0], mean[1], mean[2]});
    }
    return worst;
}

class InputFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(InputFormat, MatchesVideoconvert)
{
    gc::test::init_gstreamer();
    const std::string format = GetParam();
    const double diff = difference_to_reference("video/x-raw,format=" + format + "," + kSize,
                                                 "handtracker name=t output=left ! videoconvert");
    // Packed RGB formats are rearranged exactly; YUV differs by the chroma filters only
    // (a stride error would shear the image and differ by tens of grey levels).
    const bool rgb = format.find('Y') == std::string::npos && format.find('I') == std::string::npos &&
                     format.find('N') == std::string::npos;
    EXPECT_LE(diff, rgb ? 0.0 : 8.0) << format;
}

INSTANTIATE_TEST_SUITE_P(Handtracker, InputFormat,
                         ::testing::Values("YUY2", "NV12", "I420", "RGB", "BGR", "RGBx", "BGRx", "xRGB", "xBGR",
                                           "RGBA", "BGRA"));

class OutputFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(OutputFormat, MatchesVideoconvert)
{
    gc::test::init_gstreamer();
    const std::string format = GetParam();
    const double diff =
        difference_to_reference(std::string("video/x-raw,format=BGR,") + kSize,
                                "handtracker output=left ! video/x-raw,format=" + format + " ! videoconvert");
    const bool rgb = format != "I420" && format != "NV12";
    EXPECT_LE(diff, rgb ? 0.0 : 8.0) << format;
}

INSTANTIATE_TEST_SUITE_P(Handtracker, OutputFormat,
                         ::testing::Values("BGR", "RGB", "BGRx", "RGBx", "xRGB", "xBGR", "BGRA", "RGBA", "I420",
                                           "NV12"));

TEST(Negotiation, MismatchedViewsFailWithBothSizes)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r = run_pipeline(
        "videotestsrc num-buffers=5 ! video/x-raw,format=BGR,width=640,height=480 ! t.sink_left "
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
        return run_pipeline("filesrc location=" + png + " ! pngdec ! t.sink_left handtracker name=t particles=50 ! "
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
        "handtracker name=t output=attended ! video/x-raw,width=96,height=64 ! appsink name=out sync=false wait-on-eos=false");
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
