// imagesizelimit: a pass-through for PNG and JPEG pictures that reads the size each
// buffer's header declares. GStreamer's pngdec decodes a whole picture into memory before
// downstream can refuse its size (30000 x 30000 pixels: 15 s and 2.6 GB), so the limit has
// to be applied to the compressed bytes. A buffer that does not start with a header (a
// chunk from filesrc, a damaged file) passes for the decoder to judge.
#include "gstimagesizelimit.hpp"

#include "common/frame_limits.hpp"
#include "tools/image_header.hpp"

#include <string_view>

GST_DEBUG_CATEGORY_STATIC(gst_image_size_limit_debug);
#define GST_CAT_DEFAULT gst_image_size_limit_debug

struct _GstImageSizeLimit {
    GstBaseTransform parent;
};

G_DEFINE_TYPE(GstImageSizeLimit, gst_image_size_limit, GST_TYPE_BASE_TRANSFORM)
GST_ELEMENT_REGISTER_DEFINE(imagesizelimit, "imagesizelimit", GST_RANK_NONE, GST_TYPE_IMAGE_SIZE_LIMIT)

static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS("image/png; image/jpeg"));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS("image/png; image/jpeg"));

static GstFlowReturn gst_image_size_limit_transform_ip(GstBaseTransform* base, GstBuffer* buffer)
{
    GstMapInfo map;
    if (!gst_buffer_map(buffer, &map, GST_MAP_READ)) {
        GST_ELEMENT_ERROR(base, STREAM, FAILED, ("Cannot map the input buffer."), (nullptr));
        return GST_FLOW_ERROR;
    }
    const auto declared =
        gc::tools::image_header_size(std::string_view(reinterpret_cast<const char*>(map.data), map.size));
    gst_buffer_unmap(buffer, &map);
    if (declared && (declared->width > gc::kMaxFrameSide || declared->height > gc::kMaxFrameSide)) {
        GST_ELEMENT_ERROR(base, STREAM, FORMAT,
                          ("A picture of %d x %d pixels is over the frame limit of %d pixels a side.", declared->width,
                           declared->height, gc::kMaxFrameSide),
                          ("buffer at %" GST_TIME_FORMAT ", offset %" G_GUINT64_FORMAT,
                           GST_TIME_ARGS(GST_BUFFER_PTS(buffer)), GST_BUFFER_OFFSET(buffer)));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

static void gst_image_size_limit_class_init(GstImageSizeLimitClass* klass)
{
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);
    GstBaseTransformClass* transform_class = GST_BASE_TRANSFORM_CLASS(klass);
    GST_DEBUG_CATEGORY_INIT(gst_image_size_limit_debug, "imagesizelimit", 0, "picture size limit");
    gst_element_class_add_static_pad_template(element_class, &sink_template);
    gst_element_class_add_static_pad_template(element_class, &src_template);
    gst_element_class_set_static_metadata(
        element_class, "Picture size limit", "Filter/Image",
        "Passes PNG and JPEG pictures whose header declares at most 8192 pixels a side; a larger one stops the "
        "stream with an error naming its size before a decoder allocates it",
        "GestureCAM <gesturecam@localhost>");
    transform_class->transform_ip = gst_image_size_limit_transform_ip;
    transform_class->transform_ip_on_passthrough = TRUE;
}

static void gst_image_size_limit_init(GstImageSizeLimit* self)
{
    gst_base_transform_set_passthrough(GST_BASE_TRANSFORM(self), TRUE);
}
