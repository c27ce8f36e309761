// One frame's tracking result as the element publishes it: GstHandPointingMeta, the
// `hand-pointing` structure (element message and region-of-interest parameters).
#pragma once

#include "tracker/pointing_tracker.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/gst.h>
#include <opencv2/core.hpp>

#include <vector>

namespace gc::gst {

// Where the result sits relative to the output buffer.
struct ReportContext {
    bool incomplete = false;  // a view was missing: the tracker did not run
    bool full_view = true;    // the buffer shows a whole input view
    cv::Rect view;            // the shown rectangle of the input view, input pixels
};

GstHandPointingState meta_state(TrackState s);
GstHandPointingGesture meta_gesture(Gesture g);

// Sets `name` in s to a GstValueArray of the three doubles of v.
void set_vec3(GstStructure* s, const char* name, const cv::Vec3d& v);

// Fills every field of `meta` from `result`. `scratch` holds the contour as floats.
void fill_meta(GstHandPointingMeta& meta, const FrameResult& result, const ReportContext& context,
               std::vector<float>& scratch);

// The `hand-pointing` structure: frame, state, stereo, incomplete, left, right (stereo
// only), pointing (when the 3D ray is known) and head (when the pose is known). Fields as
// documented in docs/metadata.md. Caller owns the result.
GstStructure* pointing_structure(const FrameResult& result, const ReportContext& context, bool with_contours);

}  // namespace gc::gst
