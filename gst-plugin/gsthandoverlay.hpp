// handoverlay: draws the tracking carried by each buffer's GstHandPointingMeta (contour,
// fingertip, pointing direction, state, gesture) onto the buffer, in place.
#pragma once

#include <gst/video/gstvideofilter.h>

G_BEGIN_DECLS

#define GST_TYPE_HAND_OVERLAY (gst_hand_overlay_get_type())
G_DECLARE_FINAL_TYPE(GstHandOverlay, gst_hand_overlay, GST, HAND_OVERLAY, GstVideoFilter)

GST_ELEMENT_REGISTER_DECLARE(handoverlay);

G_END_DECLS
