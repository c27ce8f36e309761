// handtracker's pads and their caps: which sink pads may be requested together, what
// every sink pad accepts, and the output size and rate.
#pragma once

#include "gsthandtracker.hpp"

namespace gc::gst {

// Adds the sink_left, sink_right, sink (side-by-side) and src pad templates.
void add_tracker_pad_templates(GstElementClass* klass);

// The sink pad `name`, or nullptr when it was not requested.
GstVideoAggregatorPad* sink_pad(GstHandTracker* self, const char* name);

// A new sink pad from `templ`; nullptr when it exists already or cannot be combined with
// the pads there are (sink_left/sink_right or sink).
GstAggregatorPad* create_tracker_pad(GstHandTracker* self, GstPadTemplate* templ);

// Answers the caps and accept-caps queries of a sink pad; false for any other query.
bool answer_caps_query(GstHandTracker* self, GstAggregatorPad* pad, GstQuery* query);

// The output caps: the size of one view and the input rate unless downstream asks for others.
GstCaps* fixate_tracker_src_caps(GstHandTracker* self, GstCaps* caps);

}  // namespace gc::gst
