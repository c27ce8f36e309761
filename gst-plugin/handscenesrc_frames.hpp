// handscenesrc's frames: the head's pose a frame is taken at, the frame rendered from it
// into a buffer, and its ground truth posted on the bus.
#pragma once

#include "handscenesrc_state.hpp"

namespace gc::gst {

// The head's pose when the frame at `pts` is exposed; the last pose rendered from without a head.
HeadPose pose_at_capture(GstHandSceneSrc* self, GstClockTime pts);

// Renders `frame` from `pose` into `buffer`; an error on the bus when it cannot.
GstFlowReturn render_frame(GstHandSceneSrc* self, const SceneSettings& settings, guint64 frame, const HeadPose& pose,
                           GstBuffer* buffer);

// Posts the `hand-truth` element message of the frame rendered last.
void post_truth(GstHandSceneSrc* self, guint64 frame, GstClockTime pts, const SceneSettings& settings);

}  // namespace gc::gst
