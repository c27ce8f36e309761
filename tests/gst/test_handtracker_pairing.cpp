// handtracker with GstHarness on both views: frames are paired by running time (not by
// arrival order), a late or ended view yields flagged output, flushes restart tracking.
#include "gst_fixture.hpp"

#include <gst/check/gstharness.h>
#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/video.h>

#include <cstring>

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr const char* kCaps = "video/x-raw, format=BGR, width=64, height=48, framerate=30/1";

GstClockTime frame_ts(int k) { return gst_util_uint64_scale(guint64(k), GST_SECOND, 30); }

// A uniform BGR frame whose pixels all hold `value`, stamped for frame k.
GstBuffer* uniform_frame(int k, guint8 value, int width = kWidth, int height = kHeight)
{
    const gsize size = gsize(width) * gsize(height) * 3;
    GstBuffer* buffer = gst_buffer_new_allocate(nullptr, size, nullptr);
    gst_buffer_memset(buffer, 0, value, size);
    GST_BUFFER_PTS(buffer) = frame_ts(k);
    GST_BUFFER_DURATION(buffer) = frame_ts(k + 1) - frame_ts(k);
    return buffer;
}

guint8 first_pixel(GstBuffer* buffer)
{
    guint8 value = 0;
    gst_buffer_extract(buffer, 0, &value, 1);
    return value;
}

class Pairing : public ::testing::Test {
protected:
    void SetUp() override
    {
        gc::test::init_gstreamer();
        left_ = gst_harness_new_with_padnames("handtracker", "sink_left", "src");
        ASSERT_NE(left_, nullptr);
        right_ = gst_harness_new_with_element(left_->element, "sink_right", nullptr);
        ASSERT_NE(right_, nullptr);
        gst_harness_set_src_caps_str(left_, kCaps);
        gst_harness_set_src_caps_str(right_, kCaps);
    }
    void TearDown() override
    {
        if (right_) gst_harness_teardown(right_);
        if (left_) gst_harness_teardown(left_);
    }

    // Pulls one output buffer and checks its view and flags.
    void expect_output(guint8 value, bool incomplete, GstClockTime pts, guint64* frame = nullptr)
    {
        GstBuffer* out = gst_harness_pull(left_);
        ASSERT_NE(out, nullptr);
        EXPECT_EQ(first_pixel(out), value);
        EXPECT_EQ(GST_BUFFER_PTS(out), pts);
        GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(out);
        ASSERT_NE(meta, nullptr);
        EXPECT_EQ((meta->flags & GST_HAND_POINTING_FLAG_INCOMPLETE) != 0, incomplete);
        if (!incomplete) {
            EXPECT_NE(meta->flags & GST_HAND_POINTING_FLAG_STEREO, 0u);
        }
        if (frame) *frame = meta->frame;
        gst_buffer_unref(out);
    }

    GstHarness* left_ = nullptr;
    GstHarness* right_ = nullptr;
};

TEST_F(Pairing, PairsByRunningTimeNotArrivalOrder)
{
    g_object_set(left_->element, "output", 1 /* right */, nullptr);
    // The right view's first frame is for slot 1 and arrives before the left's slot 0.
    ASSERT_EQ(gst_harness_push(right_, uniform_frame(1, 21)), GST_FLOW_OK);
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(0, 10)), GST_FLOW_OK);
    expect_output(10, true, frame_ts(0));  // slot 0 has no right frame: left shown, flagged
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(1, 11)), GST_FLOW_OK);
    expect_output(21, false, frame_ts(1));
    ASSERT_EQ(gst_harness_push(right_, uniform_frame(2, 22)), GST_FLOW_OK);
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(2, 12)), GST_FLOW_OK);
    expect_output(22, false, frame_ts(2));
}

TEST_F(Pairing, EosOnOneViewKeepsTheOtherFlowingThenEndsOnBoth)
{
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(0, 10)), GST_FLOW_OK);
    ASSERT_EQ(gst_harness_push(right_, uniform_frame(0, 20)), GST_FLOW_OK);
    expect_output(10, false, frame_ts(0));
    ASSERT_TRUE(gst_harness_push_event(right_, gst_event_new_eos()));
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(1, 11)), GST_FLOW_OK);
    expect_output(11, true, frame_ts(1));
    ASSERT_TRUE(gst_harness_push_event(left_, gst_event_new_eos()));
    bool eos = false;
    for (GstEvent* ev; !eos && (ev = gst_harness_pull_event(left_)) != nullptr; gst_event_unref(ev))
        eos = GST_EVENT_TYPE(ev) == GST_EVENT_EOS;
    EXPECT_TRUE(eos);
}

TEST_F(Pairing, FlushRestartsTracking)
{
    for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(gst_harness_push(left_, uniform_frame(k, guint8(10 + k))), GST_FLOW_OK);
        ASSERT_EQ(gst_harness_push(right_, uniform_frame(k, guint8(20 + k))), GST_FLOW_OK);
        guint64 frame = 99;
        expect_output(guint8(10 + k), false, frame_ts(k), &frame);
        EXPECT_EQ(frame, guint64(k));
    }
    // A flushing seek back to the start, sent downstream of the element as an application
    // would; the harness plays the upstream elements' part of it.
    GstEvent* seek = gst_event_new_seek(1.0, GST_FORMAT_TIME, GST_SEEK_FLAG_FLUSH, GST_SEEK_TYPE_SET, 0,
                                        GST_SEEK_TYPE_NONE, GST_CLOCK_TIME_NONE);
    const guint32 seqnum = gst_event_get_seqnum(seek);
    ASSERT_TRUE(gst_harness_push_upstream_event(left_, seek));
    for (GstHarness* h : {left_, right_}) {
        GstEvent* start = gst_event_new_flush_start();
        gst_event_set_seqnum(start, seqnum);
        ASSERT_TRUE(gst_harness_push_event(h, start));
    }
    for (GstHarness* h : {left_, right_}) {
        GstEvent* stop = gst_event_new_flush_stop(TRUE);
        gst_event_set_seqnum(stop, seqnum);
        ASSERT_TRUE(gst_harness_push_event(h, stop));
        GstSegment segment;
        gst_segment_init(&segment, GST_FORMAT_TIME);
        GstEvent* seg = gst_event_new_segment(&segment);
        gst_event_set_seqnum(seg, seqnum);
        ASSERT_TRUE(gst_harness_push_event(h, seg));
    }
    ASSERT_EQ(gst_harness_push(left_, uniform_frame(0, 30)), GST_FLOW_OK);
    ASSERT_EQ(gst_harness_push(right_, uniform_frame(0, 40)), GST_FLOW_OK);
    guint64 frame = 99;
    expect_output(30, false, frame_ts(0), &frame);
    EXPECT_EQ(frame, 0u);
}

TEST_F(Pairing, RenegotiationRestartsTrackingAtTheNewSize)
{
    for (int k = 0; k < 2; ++k) {
        ASSERT_EQ(gst_harness_push(left_, uniform_frame(k, 10)), GST_FLOW_OK);
        ASSERT_EQ(gst_harness_push(right_, uniform_frame(k, 20)), GST_FLOW_OK);
        expect_output(10, false, frame_ts(k));
    }
    gst_harness_set_src_caps_str(left_, "video/x-raw, format=RGBx, width=40, height=36, framerate=30/1");
    gst_harness_set_src_caps_str(right_, "video/x-raw, format=RGBx, width=40, height=36, framerate=30/1");
    // The aggregator renegotiates its output on the first new frame and produces it once
    // the next frames are queued.
    for (int k = 2; k < 4; ++k) {
        for (GstHarness* h : {left_, right_}) {
            GstBuffer* frame = gst_buffer_new_allocate(nullptr, 40 * 36 * 4, nullptr);
            gst_buffer_memset(frame, 0, 50, 40 * 36 * 4);
            GST_BUFFER_PTS(frame) = frame_ts(k);
            GST_BUFFER_DURATION(frame) = frame_ts(k + 1) - frame_ts(k);
            ASSERT_EQ(gst_harness_push(h, frame), GST_FLOW_OK);
        }
    }
    GstBuffer* out = gst_harness_pull(left_);
    ASSERT_NE(out, nullptr);
    GstCaps* caps = gst_pad_get_current_caps(left_->sinkpad);
    GstVideoInfo info;
    ASSERT_TRUE(gst_video_info_from_caps(&info, caps));
    gst_caps_unref(caps);
    EXPECT_EQ(info.width, 40);
    EXPECT_EQ(info.height, 36);
    EXPECT_EQ(first_pixel(out), 50);
    GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(out);
    ASSERT_NE(meta, nullptr);
    EXPECT_EQ(meta->frame, 0u);  // a new size starts tracking over
    gst_buffer_unref(out);
}

TEST(PairingLive, LateViewTimesOutOnTheClock)
{
    gc::test::init_gstreamer();
    GstHarness* left = gst_harness_new_with_padnames("handtracker", "sink_left", "src");
    GstHarness* right = gst_harness_new_with_element(left->element, "sink_right", nullptr);
    gst_harness_use_testclock(left);
    gst_harness_set_upstream_latency(left, 0);
    gst_harness_set_upstream_latency(right, 0);
    gst_harness_set_src_caps_str(left, kCaps);
    gst_harness_set_src_caps_str(right, kCaps);
    ASSERT_EQ(gst_harness_push(left, uniform_frame(0, 10)), GST_FLOW_OK);
    // Nothing on the right: the aggregator waits on the clock, then outputs without it.
    ASSERT_TRUE(gst_harness_crank_single_clock_wait(left));
    GstBuffer* out = gst_harness_pull(left);
    ASSERT_NE(out, nullptr);
    EXPECT_EQ(first_pixel(out), 10);
    GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(out);
    ASSERT_NE(meta, nullptr);
    EXPECT_NE(meta->flags & GST_HAND_POINTING_FLAG_INCOMPLETE, 0u);
    gst_buffer_unref(out);
    gst_harness_teardown(right);
    gst_harness_teardown(left);
}

TEST(Pads, SideBySidePadExcludesTheEyePads)
{
    gc::test::init_gstreamer();
    GstElement* tracker = gst_element_factory_make("handtracker", nullptr);
    ASSERT_NE(tracker, nullptr);
    GstPad* left = gst_element_request_pad_simple(tracker, "sink_left");
    ASSERT_NE(left, nullptr);
    EXPECT_EQ(gst_element_request_pad_simple(tracker, "sink"), nullptr);  // not with eyes
    gst_element_release_request_pad(tracker, left);
    gst_object_unref(left);
    GstPad* packed = gst_element_request_pad_simple(tracker, "sink");
    ASSERT_NE(packed, nullptr);
    EXPECT_STREQ(GST_PAD_NAME(packed), "sink");
    EXPECT_EQ(gst_element_request_pad_simple(tracker, "sink_right"), nullptr);
    gst_element_release_request_pad(tracker, packed);
    gst_object_unref(packed);
    gst_object_unref(tracker);
}

}  // namespace
