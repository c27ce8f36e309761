// handtracker's tracking step: the tracker built from the properties, and run on the views
// of one output slot with the head's motion.
#pragma once

#include "handtracker_state.hpp"
#include "handtracker_views.hpp"

namespace gc::gst {

// (Re)creates the tracker from the settings; loads the calibration file when it changed.
// Posts an error and returns false when the file cannot be used.
bool build_tracker(GstHandTracker* self, const TrackerSettings& settings);

// Runs the tracker on the slot's views (`pose_pad`/`pose_frame` give their capture time for
// the head's pose), with the head's motion when there is a head.
GstFlowReturn track_views(GstHandTracker* self, const TrackerSettings& settings, const SlotViews& in, bool stereo,
                          GstVideoAggregatorPad* pose_pad, const GstVideoFrame* pose_frame, GstBuffer* outbuf);

// Logs each view's acquisition, loss, re-acquisition and gesture changes (INFO), and every
// tracked frame's summary (LOG).
void log_result(GstHandTracker* self, TrackerState& e, const FrameResult& r);

}  // namespace gc::gst
