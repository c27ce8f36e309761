// GstHandPointingMeta on its own: registration, defaults, contour storage, and the copy and
// scale transforms that keep it true when a buffer is copied or rescaled downstream.
#include "gst_fixture.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/video.h>

#include <memory>
#include <utility>
#include <vector>

namespace {

GstHandPointingMeta* add_filled_meta(GstBuffer* buffer, guint flags)
{
    GstHandPointingMeta* meta = gst_buffer_add_hand_pointing_meta(buffer);
    meta->frame = 7;
    meta->state = GST_HAND_POINTING_STATE_TRACKING;
    meta->flags = flags;
    meta->left.state = GST_HAND_POINTING_STATE_TRACKING;
    meta->left.x = 100.0;
    meta->left.y = 50.0;
    meta->left.bbox_x = 80;
    meta->left.bbox_y = 30;
    meta->left.bbox_width = 40;
    meta->left.bbox_height = 60;
    meta->left.fingertip_x = 130.0;
    meta->left.fingertip_y = 20.0;
    meta->left.pointing_deg = 45.0;
    const gfloat contour[] = {80.0f, 30.0f, 120.0f, 30.0f, 120.0f, 90.0f};
    gst_hand_pointing_eye_set_contour(&meta->left, contour, 3);
    meta->azimuth_deg = -12.5;
    meta->view_width = 320;
    meta->view_height = 240;
    return meta;
}

TEST(Meta, RegistersUnderItsApiName)
{
    gc::test::init_gstreamer();
    EXPECT_STREQ(g_type_name(GST_HAND_POINTING_META_API_TYPE), "GstHandPointingMetaAPI");
    EXPECT_TRUE(
        gst_meta_api_type_has_tag(GST_HAND_POINTING_META_API_TYPE, g_quark_from_static_string(GST_META_TAG_VIDEO_STR)));
    EXPECT_STREQ(gst_hand_pointing_state_to_string(GST_HAND_POINTING_STATE_LOST), "lost");
}

TEST(Meta, StartsZeroedAcquiring)
{
    gc::test::init_gstreamer();
    GstBuffer* buffer = gst_buffer_new_allocate(nullptr, 16, nullptr);
    GstHandPointingMeta* meta = gst_buffer_add_hand_pointing_meta(buffer);
    ASSERT_NE(meta, nullptr);
    EXPECT_EQ(meta->state, GST_HAND_POINTING_STATE_ACQUIRING);
    EXPECT_EQ(meta->flags, 0u);
    EXPECT_EQ(meta->left.scale, 1.0);
    EXPECT_EQ(meta->right.n_contour_points, 0u);
    EXPECT_EQ(gst_buffer_get_hand_pointing_meta(buffer), meta);
    gst_buffer_unref(buffer);
}

TEST(Meta, LongContoursAreSubsampledEvenly)
{
    GstHandPointingEye eye{};
    std::vector<gfloat> xy;
    const guint n = 3 * GST_HAND_POINTING_MAX_CONTOUR_POINTS;
    for (guint i = 0; i < n; ++i) {
        xy.push_back(gfloat(i));
        xy.push_back(gfloat(-int(i)));
    }
    gst_hand_pointing_eye_set_contour(&eye, xy.data(), n);
    ASSERT_EQ(eye.n_contour_points, guint(GST_HAND_POINTING_MAX_CONTOUR_POINTS));
    EXPECT_EQ(eye.contour[0][0], 0.0f);
    EXPECT_EQ(eye.contour[1][0], 3.0f);
    EXPECT_EQ(eye.contour[GST_HAND_POINTING_MAX_CONTOUR_POINTS - 1][1], -gfloat(n - 3));
}

TEST(Meta, CopiesWithTheBuffer)
{
    gc::test::init_gstreamer();
    GstBuffer* buffer = gst_buffer_new_allocate(nullptr, 16, nullptr);
    add_filled_meta(buffer, GST_HAND_POINTING_FLAG_STEREO);
    GstBuffer* copy = gst_buffer_copy(buffer);
    const GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(copy);
    ASSERT_NE(meta, nullptr);
    EXPECT_EQ(meta->frame, 7u);
    EXPECT_EQ(meta->flags, guint(GST_HAND_POINTING_FLAG_STEREO));
    EXPECT_EQ(meta->left.x, 100.0);
    EXPECT_EQ(meta->left.n_contour_points, 3u);
    EXPECT_EQ(meta->left.contour[2][1], 90.0f);
    EXPECT_EQ(meta->azimuth_deg, -12.5);
    gst_buffer_unref(copy);
    gst_buffer_unref(buffer);
}

struct BufferUnref {
    void operator()(GstBuffer* buffer) const { gst_buffer_unref(buffer); }
};
using BufferPtr = std::unique_ptr<GstBuffer, BufferUnref>;

// A buffer with the filled meta and its copy through the scale transform; `meta` is the copy's.
struct Scaled {
    BufferPtr source, copy;
    const GstHandPointingMeta* meta;
};

// Runs the scale transform as videoscale would, from 320x240 to 640x120.
Scaled scale_filled_meta(guint flags)
{
    gc::test::init_gstreamer();
    BufferPtr source(gst_buffer_new_allocate(nullptr, 16, nullptr));
    BufferPtr copy(gst_buffer_new_allocate(nullptr, 16, nullptr));
    add_filled_meta(source.get(), flags);
    GstVideoInfo in, out;
    gst_video_info_set_format(&in, GST_VIDEO_FORMAT_BGR, 320, 240);
    gst_video_info_set_format(&out, GST_VIDEO_FORMAT_BGR, 640, 120);
    GstVideoMetaTransform trans = {&in, &out};
    GstMeta* meta = GST_META_CAST(gst_buffer_get_hand_pointing_meta(source.get()));
    EXPECT_TRUE(
        meta->info->transform_func(copy.get(), meta, source.get(), gst_video_meta_transform_scale_get_quark(), &trans));
    const GstHandPointingMeta* scaled = gst_buffer_get_hand_pointing_meta(copy.get());
    return {std::move(source), std::move(copy), scaled};
}

TEST(Meta, ScaleTransformRescalesAFullView)
{
    const Scaled scaled = scale_filled_meta(GST_HAND_POINTING_FLAG_FULL_VIEW);
    const GstHandPointingMeta* meta = scaled.meta;
    ASSERT_NE(meta, nullptr);
    EXPECT_DOUBLE_EQ(meta->left.x, 200.0);
    EXPECT_DOUBLE_EQ(meta->left.y, 25.0);
    EXPECT_EQ(meta->left.bbox_width, 80);
    EXPECT_EQ(meta->left.bbox_height, 30);
    EXPECT_FLOAT_EQ(meta->left.contour[1][0], 240.0f);
    EXPECT_EQ(meta->view_width, 640);
    EXPECT_EQ(meta->view_height, 120);
    // 45 degrees becomes atan2(0.5, 2): the direction seen in the stretched image.
    EXPECT_NEAR(meta->left.pointing_deg, 14.036, 1e-3);
    EXPECT_EQ(meta->azimuth_deg, -12.5);  // 3D is unaffected by image scaling
}

TEST(Meta, ScaleTransformKeepsAnAttendedCrop)
{
    const Scaled scaled = scale_filled_meta(GST_HAND_POINTING_FLAG_NONE);
    const GstHandPointingMeta* meta = scaled.meta;
    ASSERT_NE(meta, nullptr);
    EXPECT_EQ(meta->left.x, 100.0);  // input pixels: the crop still shows the same region
    EXPECT_EQ(meta->view_width, 320);
}

TEST(Meta, EnumsHaveGTypesWithTheirNames)
{
    GEnumClass* gestures = G_ENUM_CLASS(g_type_class_ref(GST_TYPE_HAND_POINTING_GESTURE));
    EXPECT_STREQ(g_enum_get_value(gestures, GST_HAND_POINTING_GESTURE_FIST)->value_nick, "fist");
    EXPECT_STREQ(g_enum_get_value(gestures, GST_HAND_POINTING_GESTURE_POINTING)->value_nick, "pointing");
    g_type_class_unref(gestures);
    GEnumClass* states = G_ENUM_CLASS(g_type_class_ref(GST_TYPE_HAND_POINTING_STATE));
    EXPECT_STREQ(g_enum_get_value(states, GST_HAND_POINTING_STATE_LOST)->value_nick, "lost");
    g_type_class_unref(states);
    GFlagsClass* flags = G_FLAGS_CLASS(g_type_class_ref(GST_TYPE_HAND_POINTING_FLAGS));
    EXPECT_STREQ(g_flags_get_first_value(flags, GST_HAND_POINTING_FLAG_HAS_3D)->value_nick, "has-3d");
    g_type_class_unref(flags);
    EXPECT_TRUE(G_TYPE_IS_ENUM(GST_TYPE_HAND_POINTING_VIEW));
}

TEST(Meta, AccessorsReadTheFields)
{
    gc::test::init_gstreamer();
    GstBuffer* buffer = gst_buffer_new_allocate(nullptr, 16, nullptr);
    EXPECT_EQ(gst_hand_pointing_meta_from_buffer(buffer), nullptr);
    GstHandPointingMeta* meta = add_filled_meta(buffer, GST_HAND_POINTING_FLAG_HAS_3D);
    meta->elevation_deg = 4.0;
    meta->fingertip_mm[2] = 900.0;
    meta->left_gesture = GST_HAND_POINTING_GESTURE_POINTING;
    ASSERT_EQ(gst_hand_pointing_meta_from_buffer(buffer), meta);
    EXPECT_EQ(gst_hand_pointing_meta_get_frame(meta), 7u);
    EXPECT_EQ(gst_hand_pointing_meta_get_state(meta), GST_HAND_POINTING_STATE_TRACKING);
    EXPECT_EQ(gst_hand_pointing_meta_get_flags(meta), GST_HAND_POINTING_FLAG_HAS_3D);
    gdouble azimuth = 0.0, elevation = 0.0, x = 0.0, y = 0.0, z = 0.0, angle = 0.0;
    ASSERT_TRUE(gst_hand_pointing_meta_get_direction(meta, &azimuth, &elevation));
    EXPECT_EQ(azimuth, -12.5);
    EXPECT_EQ(elevation, 4.0);
    ASSERT_TRUE(gst_hand_pointing_meta_get_fingertip_mm(meta, nullptr, nullptr, &z));
    EXPECT_EQ(z, 900.0);
    EXPECT_FALSE(gst_hand_pointing_meta_get_head_pose(meta, nullptr, nullptr, nullptr, nullptr));
    EXPECT_EQ(gst_hand_pointing_meta_get_gesture(meta, GST_HAND_POINTING_VIEW_LEFT),
              GST_HAND_POINTING_GESTURE_POINTING);
    ASSERT_TRUE(gst_hand_pointing_meta_get_fingertip(meta, GST_HAND_POINTING_VIEW_LEFT, &x, &y, &angle));
    EXPECT_EQ(x, 130.0);
    EXPECT_EQ(y, 20.0);
    EXPECT_EQ(angle, 45.0);
    guint n = 0;
    const gfloat* contour = gst_hand_pointing_meta_get_contour(meta, GST_HAND_POINTING_VIEW_LEFT, &n);
    ASSERT_EQ(n, 6u);
    EXPECT_EQ(contour[2], 120.0f);
    EXPECT_EQ(contour[5], 90.0f);
    gst_buffer_unref(buffer);
}

TEST(Meta, AccessorsSayWhatIsUnknown)
{
    gc::test::init_gstreamer();
    GstBuffer* buffer = gst_buffer_new_allocate(nullptr, 16, nullptr);
    GstHandPointingMeta* meta = add_filled_meta(buffer, GST_HAND_POINTING_FLAG_NONE);
    meta->right.state = GST_HAND_POINTING_STATE_TRACKING;  // ignored: the meta is mono
    gdouble azimuth = 99.0;
    EXPECT_FALSE(gst_hand_pointing_meta_get_direction(meta, &azimuth, nullptr));
    EXPECT_EQ(azimuth, 99.0);
    EXPECT_EQ(gst_hand_pointing_meta_get_view_state(meta, GST_HAND_POINTING_VIEW_RIGHT),
              GST_HAND_POINTING_STATE_ACQUIRING);
    EXPECT_FALSE(gst_hand_pointing_meta_get_fingertip(meta, GST_HAND_POINTING_VIEW_RIGHT, nullptr, nullptr, nullptr));
    guint n = 5;
    gst_hand_pointing_meta_get_contour(meta, GST_HAND_POINTING_VIEW_RIGHT, &n);
    EXPECT_EQ(n, 0u);
    meta->left.state = GST_HAND_POINTING_STATE_LOST;
    EXPECT_FALSE(gst_hand_pointing_meta_get_fingertip(meta, GST_HAND_POINTING_VIEW_LEFT, nullptr, nullptr, nullptr));
    gst_buffer_unref(buffer);
}

}  // namespace
