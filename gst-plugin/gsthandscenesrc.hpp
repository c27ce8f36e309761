// handscenesrc: one eye of the synthetic pointing-hand scene (gc::sim::Scene) as a live or
// non-live video source, with the ground truth of every frame on the bus.
#pragma once

#include <gst/base/gstpushsrc.h>
#include <gst/gst.h>

G_BEGIN_DECLS

#define GST_TYPE_HAND_SCENE_SRC (gst_hand_scene_src_get_type())
G_DECLARE_FINAL_TYPE(GstHandSceneSrc, gst_hand_scene_src, GST, HAND_SCENE_SRC, GstPushSrc)

GST_ELEMENT_REGISTER_DECLARE(handscenesrc);

G_END_DECLS
