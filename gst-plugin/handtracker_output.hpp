// handtracker's output: the composed view in the output buffer, and the result published
// on it (meta, region of interest), on the bus and in the JSON lines.
#pragma once

#include "handtracker_state.hpp"
#include "handtracker_views.hpp"
#include "pointing_report.hpp"

namespace gc::gst {

// Writes the output view into `outbuf`; `context` receives what it shows.
GstFlowReturn compose_output(GstHandTracker* self, const TrackerSettings& settings, GstBuffer* outbuf,
                             const SlotViews& in, bool stereo, bool complete, int& shown, ReportContext& context);

// The result on the buffer (meta, region of interest), on the bus, and in the JSON lines.
GstFlowReturn publish(GstHandTracker* self, const TrackerSettings& settings, GstBuffer* outbuf, bool tracked, int shown,
                      const ReportContext& context);

// Opens json-location for the JSON lines (none when it is unset); an error on the bus and
// false when it cannot be opened.
bool open_json_output(GstHandTracker* self, const TrackerSettings& settings);
// Closes the JSON lines, reporting a failed close on the bus.
void close_json_output(GstHandTracker* self);

}  // namespace gc::gst
