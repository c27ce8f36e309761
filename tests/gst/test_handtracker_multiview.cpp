// handtracker's single `sink` pad the GStreamer way: it splits frames as their multiview mode
// and flags say (or the input-mode-override property), refuses plain mono video in words,
// and the two-pad form links from gst-launch without naming the pads.
#include "gst_fixture.hpp"

#include <gst/video/video.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <string>

namespace {

using gc::test::drain;
using gc::test::run_pipeline;

cv::Mat bgr_of(GstSample* sample)
{
    GstVideoInfo info;
    EXPECT_TRUE(gst_video_info_from_caps(&info, gst_sample_get_caps(sample)));
    GstVideoFrame frame;
    EXPECT_TRUE(gst_video_frame_map(&frame, &info, gst_sample_get_buffer(sample), GST_MAP_READ));
    cv::Mat copy = cv::Mat(info.height, info.width, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                           size_t(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)))
                       .clone();
    gst_video_frame_unmap(&frame);
    return copy;
}

// The source frame (colour bars, so the halves differ) and the left view handtracker passes
// on, with `properties` set on it.
std::pair<cv::Mat, cv::Mat> source_and_left_view(const std::string& properties)
{
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(
        "videotestsrc num-buffers=1 pattern=smpte ! video/x-raw,format=BGR,width=640,height=240,framerate=30/1 ! "
        "tee name=s s. ! queue ! t.sink handtracker name=t output=left particles=50 detector=motion " +
        properties +
        " ! video/x-raw,format=BGR ! appsink name=out sync=false wait-on-eos=false "
        "s. ! queue ! appsink name=src sync=false wait-on-eos=false");
    EXPECT_TRUE(pipeline);
    if (!pipeline) return {};
    std::vector<gc::test::SamplePtr> out, src;
    const gc::test::RunResult r = run_pipeline(pipeline.get(), 30 * GST_SECOND, [&] {
        out = drain(pipeline.get(), "out");
        src = drain(pipeline.get(), "src");
    });
    EXPECT_TRUE(r.eos) << r.error;
    if (out.empty() || src.empty()) return {};
    return {bgr_of(src[0].get()), bgr_of(out[0].get())};
}

TEST(Multiview, PlainMonoCapsOnSinkAreRefusedWithTheWaysToDeclareThePacking)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r = run_pipeline(
        "videotestsrc num-buffers=3 ! video/x-raw,width=640,height=240 ! t.sink handtracker name=t ! fakesink",
        20 * GST_SECOND);
    EXPECT_FALSE(r.eos);
    EXPECT_NE(r.error.find("multiview-mode=mono"), std::string::npos) << r.error;
    EXPECT_NE(r.error.find("input-mode-override"), std::string::npos) << r.error;
    EXPECT_NE(r.error.find("sink_left and sink_right"), std::string::npos) << r.error;
}

// A packing override and the region of the 640x240 source frame that is the left view.
struct Packing {
    std::string name;
    std::string properties;
    cv::Rect left_view;
};

class Unpacking : public ::testing::TestWithParam<Packing> {};

TEST_P(Unpacking, TheLeftViewIsItsRegionOfTheFrame)
{
    gc::test::init_gstreamer();
    const auto [source, left] = source_and_left_view(GetParam().properties);
    ASSERT_EQ(left.size(), GetParam().left_view.size());
    EXPECT_EQ(cv::norm(left, source(GetParam().left_view), cv::NORM_INF), 0.0);
}

// right-view-first: the frame's left half is the right eye's view, the left eye's is the other.
INSTANTIATE_TEST_SUITE_P(
    Multiview, Unpacking,
    ::testing::Values(Packing{"SideBySide", "input-mode-override=side-by-side", cv::Rect(0, 0, 320, 240)},
                      Packing{"RightViewFirst",
                              "input-mode-override=side-by-side input-flags-override=right-view-first",
                              cv::Rect(320, 0, 320, 240)},
                      Packing{"TopBottom", "input-mode-override=top-bottom", cv::Rect(0, 0, 640, 120)}),
    [](const auto& info) { return info.param.name; });

TEST(Multiview, HalfAspectViewsAreStretchedBackToFullWidth)
{
    gc::test::init_gstreamer();
    const auto [source, left] =
        source_and_left_view("input-mode-override=side-by-side input-flags-override=half-aspect");
    ASSERT_EQ(left.size(), cv::Size(640, 240));
    cv::Mat expected;
    cv::resize(source(cv::Rect(0, 0, 320, 240)), expected, cv::Size(640, 240), 0, 0, cv::INTER_LINEAR);
    EXPECT_LE(cv::norm(left, expected, cv::NORM_INF), 1.0);
}

// gst-launch's `t.` names no pad: the first link gets sink_left, the second sink_right.
TEST(Multiview, TwoUnnamedLinksBecomeLeftAndRight)
{
    gc::test::init_gstreamer();
    const gc::test::RunResult r =
        run_pipeline("handscenesrc eye=left num-buffers=5 ! t. handscenesrc eye=right num-buffers=5 ! t. "
                     "handtracker name=t particles=50 detector=motion ! fakesink",
                     30 * GST_SECOND);
    EXPECT_TRUE(r.eos) << r.error;
    const auto messages = r.named("hand-pointing", "t");
    ASSERT_EQ(messages.size(), 5u);
    EXPECT_NE(gc::test::get_child(messages.back(), "right"), nullptr);
}

}  // namespace
