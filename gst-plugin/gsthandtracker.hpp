// handtracker: pairs the left and right views by running time, tracks the pointing hand
// in both (gc::PointingTracker) and outputs one view with GstHandPointingMeta.
#pragma once

#include <gst/gst.h>
#include <gst/video/gstvideoaggregator.h>

G_BEGIN_DECLS

#define GST_TYPE_HAND_TRACKER (gst_hand_tracker_get_type())
G_DECLARE_FINAL_TYPE(GstHandTracker, gst_hand_tracker, GST, HAND_TRACKER, GstVideoAggregator)

typedef enum {
    GST_HAND_TRACKER_OUTPUT_LEFT,
    GST_HAND_TRACKER_OUTPUT_RIGHT,
    GST_HAND_TRACKER_OUTPUT_ATTENDED,
} GstHandTrackerOutput;

typedef enum {
    GST_HAND_TRACKER_MESSAGES_EVERY_FRAME,
    GST_HAND_TRACKER_MESSAGES_ON_CHANGE,
    GST_HAND_TRACKER_MESSAGES_NONE,
} GstHandTrackerMessageUpdates;

GST_ELEMENT_REGISTER_DECLARE(handtracker);

G_END_DECLS
