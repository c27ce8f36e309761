// handoverlay draws what a buffer's GstHandPointingMeta says where it says it, in the
// buffer's pixels (also when the buffer shows a crop of the input), leaves every other pixel
// alone, and passes buffers without the meta byte for byte.
#include "gst_fixture.hpp"

#include <gst/check/gstharness.h>
#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kStride = kWidth * 3;  // 480, already a multiple of 4
const guint8 kGrey = 90;

class Overlay : public ::testing::Test {
protected:
    void SetUp() override
    {
        gc::test::init_gstreamer();
        h_ = gst_harness_new("handoverlay");
        ASSERT_NE(h_, nullptr);
        gst_harness_set_src_caps_str(h_, "video/x-raw,format=BGR,width=160,height=120,framerate=30/1");
    }
    void TearDown() override
    {
        if (h_) gst_harness_teardown(h_);
    }

    static GstBuffer* grey_buffer()
    {
        GstBuffer* buffer = gst_buffer_new_allocate(nullptr, kStride * kHeight, nullptr);
        gst_buffer_memset(buffer, 0, kGrey, kStride * kHeight);
        return buffer;
    }

    // Pushes `in` and returns the output as a BGR image (a copy).
    cv::Mat push_and_read(GstBuffer* in)
    {
        GstBuffer* out = gst_harness_push_and_pull(h_, in);
        EXPECT_NE(out, nullptr);
        cv::Mat image(kHeight, kWidth, CV_8UC3);
        if (out) {
            gst_buffer_extract(out, 0, image.data, kStride * kHeight);
            gst_buffer_unref(out);
        }
        return image;
    }

    GstHarness* h_ = nullptr;
};

// A tracked hand whose contour is the square (40..80, 40..80) of the buffer, fingertip at
// its top-right corner pointing up and to the right; `view` maps input pixels to the buffer
// as handtracker's attended output does (input = view origin + buffer / scale).
void add_tracked_hand(GstBuffer* buffer, int view_x, int view_y, double scale)
{
    GstHandPointingMeta* meta = gst_buffer_add_hand_pointing_meta(buffer);
    meta->state = GST_HAND_POINTING_STATE_TRACKING;
    meta->view_x = view_x;
    meta->view_y = view_y;
    meta->view_width = int(kWidth / scale);
    meta->view_height = int(kHeight / scale);
    const auto in_x = [&](double x) { return view_x + x / scale; };
    const auto in_y = [&](double y) { return view_y + y / scale; };
    GstHandPointingEye& eye = meta->left;
    eye.state = GST_HAND_POINTING_STATE_TRACKING;
    eye.confidence = 0.8;
    eye.x = in_x(60);
    eye.y = in_y(60);
    eye.fingertip_x = in_x(80);
    eye.fingertip_y = in_y(40);
    eye.pointing_deg = 45.0;
    const gfloat square[] = {gfloat(in_x(40)), gfloat(in_y(40)), gfloat(in_x(80)), gfloat(in_y(40)),
                             gfloat(in_x(80)), gfloat(in_y(80)), gfloat(in_x(40)), gfloat(in_y(80))};
    gst_hand_pointing_eye_set_contour(&eye, square, 4);
    meta->left_gesture = GST_HAND_POINTING_GESTURE_POINTING;
}

bool changed(const cv::Mat& image, int x, int y)
{
    const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
    return p[0] != kGrey || p[1] != kGrey || p[2] != kGrey;
}

// Whether every pixel of the rectangle still has the input's grey.
bool untouched(const cv::Mat& image, const cv::Rect& r)
{
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x)
            if (changed(image, x, y)) return false;
    return true;
}

void expect_hand_drawn_at_the_square(const cv::Mat& out)
{
    // The contour's edges (mid-points of the four sides) and the palm marker are drawn ...
    EXPECT_TRUE(changed(out, 60, 40));
    EXPECT_TRUE(changed(out, 80, 60));
    EXPECT_TRUE(changed(out, 60, 80));
    EXPECT_TRUE(changed(out, 40, 60));
    EXPECT_TRUE(changed(out, 60, 60));
    // ... and the ray from the fingertip up and to the right, towards (120, 0).
    EXPECT_TRUE(changed(out, 100, 20));
    // The inside of the square away from the marker, below the square and left of it
    // (under the text line) stay as they were.
    EXPECT_TRUE(untouched(out, cv::Rect(45, 45, 8, 8)));
    EXPECT_TRUE(untouched(out, cv::Rect(0, 86, kWidth, kHeight - 86)));
    EXPECT_TRUE(untouched(out, cv::Rect(0, 40, 34, 46)));
    EXPECT_TRUE(untouched(out, cv::Rect(86, 50, 74 - 20, 30)));
}

TEST_F(Overlay, DrawsWhereTheMetaSays)
{
    GstBuffer* in = grey_buffer();
    add_tracked_hand(in, 0, 0, 1.0);
    expect_hand_drawn_at_the_square(push_and_read(in));
}

TEST_F(Overlay, MapsInputPixelsOfACroppedViewToTheBuffer)
{
    GstBuffer* in = grey_buffer();
    add_tracked_hand(in, 100, 50, 0.5);  // the buffer shows input (100, 50, 320, 240) at half size
    expect_hand_drawn_at_the_square(push_and_read(in));
}

TEST_F(Overlay, BufferWithoutMetaPassesUnchanged)
{
    GstBuffer* in = grey_buffer();
    // A pattern, so a reordering of channels or rows would show too.
    GstMapInfo map;
    ASSERT_TRUE(gst_buffer_map(in, &map, GST_MAP_WRITE));
    for (gsize i = 0; i < map.size; ++i) map.data[i] = guint8(i * 7 + i / kStride);
    const std::string before(reinterpret_cast<const char*>(map.data), map.size);
    gst_buffer_unmap(in, &map);
    const cv::Mat out = push_and_read(in);
    EXPECT_EQ(std::memcmp(out.data, before.data(), before.size()), 0);
}

TEST_F(Overlay, AcquiringHandDrawsNoContour)
{
    GstBuffer* in = grey_buffer();
    add_tracked_hand(in, 0, 0, 1.0);
    GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(in);
    meta->state = meta->left.state = GST_HAND_POINTING_STATE_ACQUIRING;
    const cv::Mat out = push_and_read(in);
    EXPECT_FALSE(changed(out, 60, 80));
    EXPECT_FALSE(changed(out, 80, 60));
}

// One tracker, two branches through a tee: the annotated one differs from the clean one
// exactly on the frames the meta calls tracking, near the drawn fingertip, and the clean
// branch keeps the tracker's own pixels.
TEST(OverlayPipeline, TeeGivesACleanAndAnAnnotatedStream)
{
    gc::test::init_gstreamer();
    const std::string description =
        "handscenesrc eye=left num-buffers=30 ! video/x-raw,width=320,height=240 ! t.sink_left "
        "handscenesrc eye=right num-buffers=30 ! video/x-raw,width=320,height=240 ! t.sink_right "
        "handtracker name=t output=left ! video/x-raw,format=BGR ! tee name=split "
        "split. ! queue ! appsink name=clean sync=false wait-on-eos=false "
        "split. ! queue ! handoverlay ! appsink name=drawn sync=false wait-on-eos=false";
    gc::test::ElementPtr pipeline = gc::test::parse_pipeline(description);
    ASSERT_TRUE(pipeline);
    std::vector<gc::test::SamplePtr> clean, drawn;
    const gc::test::RunResult r = gc::test::run_pipeline(pipeline.get(), 60 * GST_SECOND, [&] {
        clean = gc::test::drain(pipeline.get(), "clean");
        drawn = gc::test::drain(pipeline.get(), "drawn");
    });
    ASSERT_TRUE(r.eos) << r.error;
    ASSERT_EQ(clean.size(), 30u);
    ASSERT_EQ(drawn.size(), 30u);
    int tracked = 0;
    for (size_t i = 0; i < clean.size(); ++i) {
        GstBuffer* a = gst_sample_get_buffer(clean[i].get());
        GstBuffer* b = gst_sample_get_buffer(drawn[i].get());
        const GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(a);
        ASSERT_NE(meta, nullptr);
        const gsize size = gst_buffer_get_size(a);
        std::string pa(size, '\0'), pb(size, '\0');
        gst_buffer_extract(a, 0, pa.data(), size);
        gst_buffer_extract(b, 0, pb.data(), size);
        if (meta->left.state != GST_HAND_POINTING_STATE_TRACKING) continue;
        ++tracked;
        EXPECT_NE(pa, pb) << "frame " << i;
        // The fingertip's ring (radius 5) passes 5 pixels to its right.
        const int x = int(meta->left.fingertip_x + 0.5) + 5;
        const int y = int(meta->left.fingertip_y + 0.5);
        const size_t at = size_t(y) * 320 * 3 + size_t(x) * 3;
        EXPECT_NE(pa.compare(at, 3, pb, at, 3), 0) << "frame " << i << " at (" << x << ", " << y << ")";
    }
    EXPECT_GT(tracked, 10);
}

}  // namespace
