#include "handtracker_caps.hpp"

#include "handtracker_state.hpp"
#include "handtracker_views.hpp"
#include "video_bgr.hpp"

#include "common/frame_limits.hpp"

#include <gst/video/video.h>

namespace gc::gst {

namespace {

// The frame-size limit spelt out, as static caps need a literal.
static_assert(gc::kMaxFrameSide == 8192, "VIDEO_CAPS states gc::kMaxFrameSide");
#define VIDEO_CAPS(formats)                                                                                            \
    "video/x-raw, format = (string) { " formats " }, width = (int) [ 32, 8192 ], "                                     \
    "height = (int) [ 32, 8192 ], framerate = (fraction) [ 0/1, 2147483647/1 ]"

static GstStaticPadTemplate sink_left_template =
    GST_STATIC_PAD_TEMPLATE("sink_left", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate sink_right_template =
    GST_STATIC_PAD_TEMPLATE("sink_right", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate sink_packed_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS(GC_OUTPUT_FORMATS)));

// Upstream reports refused caps only as not-negotiated: a frame size over the limit is named
// on the bus (a warning, since upstream may still choose smaller caps).
void warn_if_too_large(GstHandTracker* self, GstPad* pad, GstCaps* caps)
{
    const GstStructure* s = gst_caps_is_fixed(caps) ? gst_caps_get_structure(caps, 0) : nullptr;
    int width = 0, height = 0;
    if (!s || !gst_structure_get_int(s, "width", &width) || !gst_structure_get_int(s, "height", &height) ||
        (width <= gc::kMaxFrameSide && height <= gc::kMaxFrameSide))
        return;
    GST_ELEMENT_WARNING(self, STREAM, FORMAT,
                        ("%s: frames of %dx%d are larger than the limit of %dx%d pixels.", GST_PAD_NAME(pad), width,
                         height, gc::kMaxFrameSide, gc::kMaxFrameSide),
                        ("the caps are refused"));
}

PackedLayout sink_layout(GstHandTracker* self, const GstVideoInfo& info)
{
    const TrackerSettings settings = read_settings(self);
    return packed_layout(info, settings.input_mode_override, settings.input_flags_override);
}

// `sink` takes both views in one frame; caps that do not say how they are packed (plain
// mono video, say) are refused in words, with the ways to say it.
bool accept_packed_caps(GstHandTracker* self, GstCaps* caps)
{
    GstVideoInfo info;
    if (!gst_caps_is_fixed(caps) || !gst_video_info_from_caps(&info, caps)) return true;  // the template check decides
    const PackedLayout layout = sink_layout(self, info);
    if (layout.known()) return true;
    const char* mode = gst_video_multiview_mode_to_caps_string(layout.mode);
    GST_ELEMENT_ERROR(self, STREAM, FORMAT,
                      ("The sink pad takes both views in one frame, but its caps give multiview-mode=%s. Declare "
                       "the packing (multiview-mode=side-by-side or top-bottom in the caps, e.g. with capssetter, or "
                       "input-mode-override=side-by-side), or link two cameras to sink_left and sink_right.",
                       mode ? mode : "mono"),
                      ("caps: %" GST_PTR_FORMAT, caps));
    return false;
}

// The size of one view as the pads currently describe it.
bool current_view_size(GstHandTracker* self, int& width, int& height)
{
    for (const char* name : {"sink_left", "sink_right", "sink"}) {
        GstVideoAggregatorPad* pad = sink_pad(self, name);
        if (!pad) continue;
        GST_OBJECT_LOCK(self);
        GstVideoInfo info = pad->info;
        GST_OBJECT_UNLOCK(self);
        if (!info.finfo || GST_VIDEO_INFO_FORMAT(&info) == GST_VIDEO_FORMAT_UNKNOWN || info.width == 0) continue;
        cv::Size view(info.width, info.height);
        if (g_str_equal(name, "sink")) view = sink_layout(self, info).view_size(view);
        width = view.width;
        height = view.height;
        return true;
    }
    return false;
}

}  // namespace

void add_tracker_pad_templates(GstElementClass* klass)
{
    gst_element_class_add_static_pad_template_with_gtype(klass, &sink_left_template, GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(klass, &sink_right_template, GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(klass, &sink_packed_template, GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(klass, &src_template, GST_TYPE_AGGREGATOR_PAD);
}

GstVideoAggregatorPad* sink_pad(GstHandTracker* self, const char* name)
{
    GstPad* pad = gst_element_get_static_pad(GST_ELEMENT(self), name);
    if (pad) gst_object_unref(pad);  // the element keeps its pads alive while streaming
    return pad ? GST_VIDEO_AGGREGATOR_PAD(pad) : nullptr;
}

GstAggregatorPad* create_tracker_pad(GstHandTracker* self, GstPadTemplate* templ, const gchar* req_name)
{
    GstElement* element = GST_ELEMENT(self);
    // A link that names no pad (gst-launch's `t.`) asks for the first fitting template
    // twice: the second camera gets sink_right.
    if (!req_name && g_str_equal(GST_PAD_TEMPLATE_NAME_TEMPLATE(templ), "sink_left") && sink_pad(self, "sink_left"))
        templ = gst_element_class_get_pad_template(GST_ELEMENT_GET_CLASS(element), "sink_right");
    const gchar* name = GST_PAD_TEMPLATE_NAME_TEMPLATE(templ);
    if (GstPad* existing = gst_element_get_static_pad(element, name)) {
        gst_object_unref(existing);
        GST_WARNING_OBJECT(self, "pad %s already exists", name);
        return nullptr;
    }
    const bool packed = g_str_equal(name, "sink");
    const bool have_packed = sink_pad(self, "sink") != nullptr;
    const bool have_eyes = sink_pad(self, "sink_left") || sink_pad(self, "sink_right");
    if ((packed && have_eyes) || (!packed && have_packed)) {
        GST_WARNING_OBJECT(self, "pad %s cannot be combined with %s", name,
                           packed ? "sink_left/sink_right" : "the side-by-side pad sink");
        return nullptr;
    }
    return GST_AGGREGATOR_PAD(g_object_new(GST_PAD_TEMPLATE_GTYPE(templ), "name", name, "direction", GST_PAD_SINK,
                                           "template", templ, nullptr));
}

// Any size and format of the template on every sink pad, whatever downstream wants: the
// element converts itself, and a size mismatch between the views is reported in words
// when the frames meet instead of failing upstream's negotiation without a reason.
bool answer_caps_query(GstHandTracker* self, GstAggregatorPad* pad, GstQuery* query)
{
    switch (GST_QUERY_TYPE(query)) {
    case GST_QUERY_CAPS: {
        GstCaps* filter = nullptr;
        gst_query_parse_caps(query, &filter);
        GstCaps* caps = gst_pad_get_pad_template_caps(GST_PAD(pad));
        if (filter) {
            GstCaps* both = gst_caps_intersect_full(filter, caps, GST_CAPS_INTERSECT_FIRST);
            gst_caps_unref(caps);
            caps = both;
        }
        gst_query_set_caps_result(query, caps);
        gst_caps_unref(caps);
        return true;
    }
    case GST_QUERY_ACCEPT_CAPS: {
        GstCaps* caps = nullptr;
        gst_query_parse_accept_caps(query, &caps);
        GstCaps* templ = gst_pad_get_pad_template_caps(GST_PAD(pad));
        gboolean accepted = gst_caps_is_subset(caps, templ);
        gst_caps_unref(templ);
        if (!accepted)
            warn_if_too_large(self, GST_PAD(pad), caps);
        else if (g_str_equal(GST_PAD_NAME(pad), "sink"))
            accepted = accept_packed_caps(self, caps);
        gst_query_set_accept_caps_result(query, accepted);
        return true;
    }
    default:
        return false;
    }
}

// The output follows the size of one view unless downstream asks for another.
GstCaps* fixate_tracker_src_caps(GstHandTracker* self, GstCaps* caps)
{
    int width = 640, height = 480;
    current_view_size(self, width, height);
    gint fps_n = 30, fps_d = 1;
    for (const char* name : {"sink_left", "sink_right", "sink"}) {
        GstVideoAggregatorPad* pad = sink_pad(self, name);
        if (pad && pad->info.finfo && GST_VIDEO_INFO_FPS_N(&pad->info) > 0) {
            fps_n = GST_VIDEO_INFO_FPS_N(&pad->info);
            fps_d = GST_VIDEO_INFO_FPS_D(&pad->info);
            break;
        }
    }
    caps = gst_caps_make_writable(caps);
    GstStructure* s = gst_caps_get_structure(caps, 0);
    gst_structure_fixate_field_nearest_int(s, "width", width);
    gst_structure_fixate_field_nearest_int(s, "height", height);
    gst_structure_fixate_field_nearest_fraction(s, "framerate", fps_n, fps_d);
    if (gst_structure_has_field(s, "pixel-aspect-ratio"))
        gst_structure_fixate_field_nearest_fraction(s, "pixel-aspect-ratio", 1, 1);
    return gst_caps_fixate(caps);
}

}  // namespace gc::gst
