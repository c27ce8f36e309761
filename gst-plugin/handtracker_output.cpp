#include "handtracker_output.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/gstvideometa.h>

#include <exception>
#include <string>

namespace gc::gst {

namespace {

using Settings = TrackerSettings;

bool should_post(TrackerState& e, GstHandTrackerMessageUpdates mode, gc::TrackState state)
{
    switch (mode) {
    case GST_HAND_TRACKER_MESSAGES_NONE:
        return false;
    case GST_HAND_TRACKER_MESSAGES_ON_CHANGE:
        if (e.stream.last_posted_state == state) return false;
        break;
    case GST_HAND_TRACKER_MESSAGES_EVERY_FRAME:
        break;
    }
    e.stream.last_posted_state = state;
    return true;
}

// The running time and stream time of an output timestamp.
void output_times(GstHandTracker* self, GstClockTime pts, GstClockTime& running, GstClockTime& stream)
{
    GstAggregator* agg = GST_AGGREGATOR(self);
    GST_OBJECT_LOCK(agg->srcpad);
    const GstSegment* segment = &GST_AGGREGATOR_PAD(agg->srcpad)->segment;
    running = gst_segment_to_running_time(segment, GST_FORMAT_TIME, pts);
    stream = gst_segment_to_stream_time(segment, GST_FORMAT_TIME, pts);
    GST_OBJECT_UNLOCK(agg->srcpad);
}

void post_message(GstHandTracker* self, GstBuffer* outbuf, const gc::FrameResult& result,
                  const gc::gst::ReportContext& context)
{
    GstStructure* s = gc::gst::pointing_structure(result, context, true);
    const GstClockTime pts = GST_BUFFER_PTS(outbuf);
    GstClockTime running = GST_CLOCK_TIME_NONE, stream = GST_CLOCK_TIME_NONE;
    output_times(self, pts, running, stream);
    gst_structure_set(s, "timestamp", G_TYPE_UINT64, pts, "running-time", G_TYPE_UINT64, running, "stream-time",
                      G_TYPE_UINT64, stream, "duration", G_TYPE_UINT64, GST_BUFFER_DURATION(outbuf), "skipped-qos",
                      G_TYPE_UINT64, self->stats->skipped(), nullptr);
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

// The region of interest in the output buffer's pixels: the output view's hand box mapped
// through the crop and the scaling.
void add_region_of_interest(GstBuffer* outbuf, const gc::FrameResult& result, bool right_view, const cv::Rect& view,
                            cv::Size out, const gc::gst::ReportContext& context)
{
    const gc::EyeEstimate& eye = right_view ? result.right : result.left;
    if (eye.state == gc::TrackState::Acquiring || eye.bbox.area() <= 0 || view.area() <= 0) return;
    const double sx = double(out.width) / view.width;
    const double sy = double(out.height) / view.height;
    cv::Rect box(int((eye.bbox.x - view.x) * sx), int((eye.bbox.y - view.y) * sy), int(eye.bbox.width * sx),
                 int(eye.bbox.height * sy));
    box &= cv::Rect(0, 0, out.width, out.height);
    if (box.area() <= 0) return;
    GstVideoRegionOfInterestMeta* roi = gst_buffer_add_video_region_of_interest_meta(
        outbuf, "hand", guint(box.x), guint(box.y), guint(box.width), guint(box.height));
    gst_video_region_of_interest_meta_add_param(roi, gc::gst::pointing_structure(result, context, false));
}

}  // namespace

GstFlowReturn compose_output(GstHandTracker* self, const Settings& settings, GstBuffer* outbuf,
                             const gc::gst::SlotViews& in, bool stereo, bool complete, int& shown,
                             gc::gst::ReportContext& context)
{
    TrackerState& e = *self->state;
    const gc::FrameResult& result = e.tracker->last();
    GstVideoFrame out;
    if (!gst_video_frame_map(&out, &GST_VIDEO_AGGREGATOR(self)->info, outbuf, GST_MAP_WRITE)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot map the output buffer."), (nullptr));
        return GST_FLOW_ERROR;
    }
    const cv::Size out_size(GST_VIDEO_FRAME_WIDTH(&out), GST_VIDEO_FRAME_HEIGHT(&out));
    shown = settings.output == GST_HAND_TRACKER_OUTPUT_RIGHT && stereo ? 1 : 0;
    if (!in.have[shown]) shown = in.have[0] ? 0 : 1;  // an incomplete pair shows the view that is there
    gc::gst::ViewChoice choice;
    choice.shown = shown;
    choice.draw = settings.draw;
    choice.attended = settings.output == GST_HAND_TRACKER_OUTPUT_ATTENDED && shown == 0 && in.have[0];
    if (choice.attended && e.stream.target)
        choice.target = gc::gst::target_in_view(
            e.stream.target, settings.target_region_mm,
            e.calibration ? *e.calibration : gc::default_calibration(in.views[0].size()), result);
    context.incomplete = !complete;
    context.full_view = !choice.attended;
    std::span<const gc::Particle> particles;
    if (settings.draw && complete) particles = e.tracker->particles(shown == 1 ? gc::Eye::Right : gc::Eye::Left);
    try {
        context.view = gc::gst::compose_view(in, choice, result, particles, out_size, e.stream.attention, e.overlay,
                                             e.canvas, e.scaled);
        e.writer.write(e.scaled, out);
    } catch (const std::exception& err) {
        gst_video_frame_unmap(&out);
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot compose the output frame."), ("%s", err.what()));
        return GST_FLOW_ERROR;
    }
    gst_video_frame_unmap(&out);
    return GST_FLOW_OK;
}

GstFlowReturn publish(GstHandTracker* self, const Settings& settings, GstBuffer* outbuf, bool tracked, int shown,
                      const gc::gst::ReportContext& context)
{
    TrackerState& e = *self->state;
    const gc::FrameResult& result = e.tracker->last();
    const cv::Size out_size(GST_VIDEO_INFO_WIDTH(&GST_VIDEO_AGGREGATOR(self)->info),
                            GST_VIDEO_INFO_HEIGHT(&GST_VIDEO_AGGREGATOR(self)->info));
    if (GstHandPointingMeta* meta = gst_buffer_add_hand_pointing_meta(outbuf))
        gc::gst::fill_meta(*meta, result, context, e.contour_scratch);
    add_region_of_interest(outbuf, result, shown == 1, context.view, out_size, context);
    if (should_post(e, settings.message_updates, result.state)) post_message(self, outbuf, result, context);
    if (!tracked || !e.json) return GST_FLOW_OK;
    e.json_line = gc::to_json_line(result);
    // Output frames dropped under QoS since the previous line are counted on this one; the tool
    // never drops, so its lines never have the key.
    if (const guint64 skipped = self->stats->take_skipped_since_line())
        e.json_line.insert(e.json_line.size() - 1, ",\"skipped_qos\":" + std::to_string(skipped));
    e.json_line += '\n';
    try {
        e.json->write_line(e.json_line);
    } catch (const gc::OutputError& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, WRITE, ("Cannot write to \"%s\".", e.json_path.c_str()), ("%s", err.what()));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

bool open_json_output(GstHandTracker* self, const Settings& settings)
{
    TrackerState& e = *self->state;
    e.json.reset();
    e.json_path = settings.json_location;
    if (!settings.json_location.empty()) {
        try {
            e.json = gc::LineOutput::create(settings.json_location);
        } catch (const gc::OutputError& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE, ("Cannot open \"%s\" for writing.", e.json_path.c_str()),
                              ("%s", err.what()));
            return false;
        }
    }
    return true;
}

void close_json_output(GstHandTracker* self)
{
    TrackerState& e = *self->state;
    if (e.json) {
        try {
            e.json->close();
        } catch (const gc::OutputError& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, CLOSE, ("Cannot close \"%s\".", e.json_path.c_str()), ("%s", err.what()));
        }
        e.json.reset();
    }
}

}  // namespace gc::gst
