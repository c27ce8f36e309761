// handtracker's head: the head URI and token checked at start, the link built for the
// views' size, the head's pose and motion for each tracked pair, and each result handed
// back for steering.
#pragma once

#include "handtracker_state.hpp"

#include <gst/video/video.h>

namespace gc::gst {

// Checks the head URI and reads the token file (an error on the bus when either fails);
// no link is made before the first views.
bool prepare_head(GstHandTracker* self, const TrackerSettings& settings);

// The head's pose when the views of `pose_frame` (on `pose_pad`) were taken and the image
// motion it caused, into `at`; nothing without a head. Builds the link when needed.
GstFlowReturn head_at_capture(GstHandTracker* self, const TrackerSettings& settings, cv::Size size,
                              GstVideoAggregatorPad* pose_pad, const GstVideoFrame* pose_frame, GstBuffer* outbuf,
                              headctl::HeadAtCapture& at);

// Hands a tracked frame's result to the head link, warning once per episode when the views
// come too late to steer from (the head then holds).
void steer_head(GstHandTracker* self, const TrackerSettings& settings, const FrameResult& result);

}  // namespace gc::gst
