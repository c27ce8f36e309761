// handoverlay: a GstVideoFilter working in place. Buffers without GstHandPointingMeta pass
// untouched; the others get the same drawing as handtracker's `draw`, from the meta alone,
// so one tracker can feed a clean and an annotated branch through a tee.
#include "gsthandoverlay.hpp"

#include "meta_estimate.hpp"
#include "tracking_overlay.hpp"
#include "video_bgr.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/video.h>

#include <exception>

GST_DEBUG_CATEGORY_STATIC(gst_hand_overlay_debug);
#define GST_CAT_DEFAULT gst_hand_overlay_debug

// Formats whose round trip through BGR is exact, so only the drawn pixels change.
#define GC_OVERLAY_FORMATS "BGR, RGB, BGRx, RGBx, xRGB, xBGR"

enum GstHandOverlayView { GST_HAND_OVERLAY_VIEW_LEFT, GST_HAND_OVERLAY_VIEW_RIGHT };

enum { PROP_0, PROP_VIEW };

struct _GstHandOverlay {
    GstVideoFilter parent;
    GstHandOverlayView view;
    struct Scratch {
        gc::gst::BgrReader reader;
        cv::Mat canvas;
        gc::gst::BgrWriter writer;
        gc::gst::TrackingOverlay overlay;
    } * scratch;
};

G_DEFINE_TYPE(GstHandOverlay, gst_hand_overlay, GST_TYPE_VIDEO_FILTER)
GST_ELEMENT_REGISTER_DEFINE(handoverlay, "handoverlay", GST_RANK_NONE, GST_TYPE_HAND_OVERLAY)

#define GST_TYPE_HAND_OVERLAY_VIEW (gst_hand_overlay_view_get_type())
static GType gst_hand_overlay_view_get_type()
{
    static GType type = 0;
    static const GEnumValue values[] = {
        {GST_HAND_OVERLAY_VIEW_LEFT, "The left view's estimate (handtracker output=left or attended)", "left"},
        {GST_HAND_OVERLAY_VIEW_RIGHT, "The right view's estimate (handtracker output=right)", "right"},
        {0, nullptr, nullptr},
    };
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstHandOverlayView", values));
    return type;
}

static GstStaticPadTemplate sink_template = GST_STATIC_PAD_TEMPLATE(
    "sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS(GST_VIDEO_CAPS_MAKE("{ " GC_OVERLAY_FORMATS " }")));
static GstStaticPadTemplate src_template = GST_STATIC_PAD_TEMPLATE(
    "src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(GST_VIDEO_CAPS_MAKE("{ " GC_OVERLAY_FORMATS " }")));

static GstFlowReturn gst_hand_overlay_transform_frame_ip(GstVideoFilter* filter, GstVideoFrame* frame)
{
    GstHandOverlay* self = GST_HAND_OVERLAY(filter);
    const GstHandPointingMeta* meta = gst_buffer_get_hand_pointing_meta(frame->buffer);
    if (!meta) return GST_FLOW_OK;
    GST_OBJECT_LOCK(self);
    const bool right = self->view == GST_HAND_OVERLAY_VIEW_RIGHT;
    GST_OBJECT_UNLOCK(self);
    try {
        auto& s = *self->scratch;
        s.reader.read(*frame).copyTo(s.canvas);
        const gc::EyeEstimate eye = gc::gst::eye_from_meta(*meta, right, s.canvas.size());
        const gc::Pointing3D pointing = gc::gst::pointing_from_meta(*meta);
        s.overlay.draw(s.canvas, eye, {}, pointing.valid ? &pointing : nullptr);
        s.writer.write(s.canvas, *frame);
    } catch (const std::exception& e) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("cannot draw the tracking"), ("%s", e.what()));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

static void gst_hand_overlay_set_property(GObject* object, guint id, const GValue* value, GParamSpec* pspec)
{
    GstHandOverlay* self = GST_HAND_OVERLAY(object);
    if (id != PROP_VIEW) {
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
        return;
    }
    GST_OBJECT_LOCK(self);
    self->view = GstHandOverlayView(g_value_get_enum(value));
    GST_OBJECT_UNLOCK(self);
}

static void gst_hand_overlay_get_property(GObject* object, guint id, GValue* value, GParamSpec* pspec)
{
    GstHandOverlay* self = GST_HAND_OVERLAY(object);
    if (id != PROP_VIEW) {
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
        return;
    }
    GST_OBJECT_LOCK(self);
    g_value_set_enum(value, self->view);
    GST_OBJECT_UNLOCK(self);
}

static void gst_hand_overlay_finalize(GObject* object)
{
    delete GST_HAND_OVERLAY(object)->scratch;
    G_OBJECT_CLASS(gst_hand_overlay_parent_class)->finalize(object);
}

static void gst_hand_overlay_class_init(GstHandOverlayClass* klass)
{
    GObjectClass* gobject_class = G_OBJECT_CLASS(klass);
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);

    GST_DEBUG_CATEGORY_INIT(gst_hand_overlay_debug, "handoverlay", 0, "draws GstHandPointingMeta");

    gobject_class->set_property = gst_hand_overlay_set_property;
    gobject_class->get_property = gst_hand_overlay_get_property;
    gobject_class->finalize = gst_hand_overlay_finalize;
    g_object_class_install_property(
        gobject_class, PROP_VIEW,
        g_param_spec_enum("view", "View", "Whose estimate to draw: the view the buffers show",
                          GST_TYPE_HAND_OVERLAY_VIEW, GST_HAND_OVERLAY_VIEW_LEFT,
                          GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS | GST_PARAM_MUTABLE_PLAYING)));

    gst_element_class_add_static_pad_template(element_class, &sink_template);
    gst_element_class_add_static_pad_template(element_class, &src_template);
    gst_element_class_set_static_metadata(
        element_class, "Hand tracking overlay", "Filter/Effect/Video",
        "Draws the tracking of each buffer's GstHandPointingMeta (contour, fingertip, pointing direction, "
        "state, gesture) onto the video; buffers without the meta pass unchanged",
        "GestureCAM <gesturecam@localhost>");

    GST_VIDEO_FILTER_CLASS(klass)->transform_frame_ip = gst_hand_overlay_transform_frame_ip;
    gst_type_mark_as_plugin_api(GST_TYPE_HAND_OVERLAY_VIEW, GstPluginAPIFlags(0));
}

static void gst_hand_overlay_init(GstHandOverlay* self)
{
    self->view = GST_HAND_OVERLAY_VIEW_LEFT;
    self->scratch = new _GstHandOverlay::Scratch();
}
