// imagesizelimit: before a PNG or JPEG decoder, refuses a picture whose header declares more
// than the product's frame limit, so that the decoder never allocates it.
#pragma once

#include <gst/base/gstbasetransform.h>
#include <gst/gst.h>

G_BEGIN_DECLS

#define GST_TYPE_IMAGE_SIZE_LIMIT (gst_image_size_limit_get_type())
G_DECLARE_FINAL_TYPE(GstImageSizeLimit, gst_image_size_limit, GST, IMAGE_SIZE_LIMIT, GstBaseTransform)

GST_ELEMENT_REGISTER_DECLARE(imagesizelimit);

G_END_DECLS
