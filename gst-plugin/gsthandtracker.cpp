// handtracker: GObject glue over gc::PointingTracker. GstVideoAggregator pairs the views
// by running time and hands aggregate_frames() the prepared frame of every pad for one
// output slot; this file converts them to BGR, runs the shared tracker code path and
// publishes the result (meta, region of interest, bus message, optional JSON lines).
#include "gsthandtracker.hpp"

#include "handtracker_caps.hpp"
#include "handtracker_director.hpp"
#include "handtracker_head.hpp"
#include "handtracker_output.hpp"
#include "handtracker_settings.hpp"
#include "handtracker_state.hpp"
#include "handtracker_tracking.hpp"
#include "handtracker_views.hpp"

#include <gst/video/video.h>

#include <array>
#include <atomic>
#include <exception>

GST_DEBUG_CATEGORY(gst_hand_tracker_debug);
#define GST_CAT_DEFAULT gst_hand_tracker_debug

using namespace gc::gst;
using Settings = TrackerSettings;

G_DEFINE_TYPE(GstHandTracker, gst_hand_tracker, GST_TYPE_VIDEO_AGGREGATOR)
GST_ELEMENT_REGISTER_DEFINE(handtracker, "handtracker", GST_RANK_NONE, GST_TYPE_HAND_TRACKER)

// ---------------------------------------------------------------------------------------
// Pads

static GstAggregatorPad* gst_hand_tracker_create_new_pad(GstAggregator* agg, GstPadTemplate* templ,
                                                         const gchar* req_name, const GstCaps* /*caps*/)
{
    return create_tracker_pad(GST_HAND_TRACKER(agg), templ, req_name);
}

static gboolean gst_hand_tracker_sink_query(GstAggregator* agg, GstAggregatorPad* pad, GstQuery* query)
{
    if (answer_caps_query(GST_HAND_TRACKER(agg), pad, query)) return TRUE;
    return GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->sink_query(agg, pad, query);
}

static GstCaps* gst_hand_tracker_fixate_src_caps(GstAggregator* agg, GstCaps* caps)
{
    return fixate_tracker_src_caps(GST_HAND_TRACKER(agg), caps);
}

// ---------------------------------------------------------------------------------------
// Tracking

static GstFlowReturn size_mismatch(GstHandTracker* self, const GstVideoFrame* left, const GstVideoFrame* right)
{
    GST_ELEMENT_ERROR(self, CORE, NEGOTIATION,
                      ("sink_left is %dx%d but sink_right is %dx%d", GST_VIDEO_FRAME_WIDTH(left),
                       GST_VIDEO_FRAME_HEIGHT(left), GST_VIDEO_FRAME_WIDTH(right), GST_VIDEO_FRAME_HEIGHT(right)),
                      ("the two views of a stereo pair must have the same size"));
    return GST_FLOW_NOT_NEGOTIATED;
}

static GstFlowReturn process_slot(GstHandTracker* self, GstBuffer* outbuf, bool& tracked_out)
{
    TrackerState& e = *self->state;
    const Settings settings = read_settings(self);
    if (self->rebuild->exchange(false) || !e.tracker) {
        if (!build_tracker(self, settings)) return GST_FLOW_ERROR;
    }
    if (self->flushed->exchange(false)) e.forget();

    GstVideoAggregatorPad* packed_pad = sink_pad(self, "sink");
    GstVideoAggregatorPad* left_pad = sink_pad(self, "sink_left");
    GstVideoAggregatorPad* right_pad = sink_pad(self, "sink_right");
    const GstVideoFrame* packed = packed_pad ? gst_video_aggregator_pad_get_prepared_frame(packed_pad) : nullptr;
    const GstVideoFrame* left = left_pad ? gst_video_aggregator_pad_get_prepared_frame(left_pad) : nullptr;
    const GstVideoFrame* right = right_pad ? gst_video_aggregator_pad_get_prepared_frame(right_pad) : nullptr;
    const bool stereo = packed_pad != nullptr || (left_pad != nullptr && right_pad != nullptr);
    if (!packed_pad && views_ready(left) && views_ready(right) &&
        (GST_VIDEO_FRAME_WIDTH(left) != GST_VIDEO_FRAME_WIDTH(right) ||
         GST_VIDEO_FRAME_HEIGHT(left) != GST_VIDEO_FRAME_HEIGHT(right)))
        return size_mismatch(self, left, right);
    gc::gst::SlotViews in;
    try {
        const gc::gst::PackedLayout layout =
            packed_pad
                ? gc::gst::packed_layout(packed_pad->info, settings.input_mode_override, settings.input_flags_override)
                : gc::gst::PackedLayout{};
        gc::gst::read_views(e.readers, e.halves, packed, layout, left, right, in);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, STREAM, FORMAT, ("Cannot read an input frame."), ("%s", err.what()));
        return GST_FLOW_ERROR;
    }

    // Track when the pair is complete (mono: the left view alone) and not the pair tracked
    // last time: a live aggregator repeats its pads' last frames when a source is late or
    // at EOS, and a frame tracked twice would count as a hand that stood still.
    const bool complete = stereo ? (in.have[0] && in.have[1]) : in.have[0];
    auto pts_of = [](const GstVideoFrame* f) {
        return views_ready(f) ? GST_BUFFER_PTS(f->buffer) : GST_CLOCK_TIME_NONE;
    };
    const std::array<GstClockTime, 2> inputs = {pts_of(packed_pad ? packed : left),
                                                packed_pad ? GST_CLOCK_TIME_NONE : pts_of(right)};
    const bool repeated = complete && e.stream.tracked_inputs == inputs && GST_CLOCK_TIME_IS_VALID(inputs[0]);
    const bool tracked = complete && !repeated;
    tracked_out = tracked;
    if (tracked) {
        e.stream.tracked_inputs = inputs;
        const GstFlowReturn ret = track_views(self, settings, in, stereo, packed_pad ? packed_pad : left_pad,
                                              packed_pad ? packed : left, outbuf);
        if (ret != GST_FLOW_OK) return ret;
        log_result(self, e, e.tracker->last());
        pick_target(self, settings, e.tracker->last());
        if (e.head) steer_head(self, settings, e.tracker->last());
        direct_camera(self, settings, e.tracker->last());
    }
    int shown = 0;
    gc::gst::ReportContext context;
    const GstFlowReturn ret = compose_output(self, settings, outbuf, in, stereo, complete, shown, context);
    if (ret != GST_FLOW_OK) return ret;
    return publish(self, settings, outbuf, tracked, shown, context);
}

// One output frame, timed: the time it takes is part of the latency the element reports, so a
// live pipeline's sinks wait for it instead of finding every frame late.
static GstFlowReturn gst_hand_tracker_aggregate_frames(GstVideoAggregator* vagg, GstBuffer* outbuf)
{
    GstHandTracker* self = GST_HAND_TRACKER(vagg);
    const gint64 start_us = g_get_monotonic_time();
    bool tracked = false;
    const GstFlowReturn ret = process_slot(self, outbuf, tracked);
    const GstClockTime took = GstClockTime(g_get_monotonic_time() - start_us) * GST_USECOND;
    GST_LOG_OBJECT(self, "output frame %" GST_TIME_FORMAT " made in %.1f ms%s", GST_TIME_ARGS(GST_BUFFER_PTS(outbuf)),
                   double(took) / GST_MSECOND, tracked ? "" : " (not tracked)");
    if (const auto latency = self->stats->frame_processed(took, tracked)) {
        GST_DEBUG_OBJECT(self, "processing latency now %" GST_TIME_FORMAT, GST_TIME_ARGS(*latency));
        gst_aggregator_set_latency(GST_AGGREGATOR(self), *latency, *latency);
    }
    return ret;
}

// GstVideoAggregator drops an output frame that QoS says would be late and posts a QoS message
// for it; the drop is counted here, as the subclass is not called for that frame.
static gboolean gst_hand_tracker_post_message(GstElement* element, GstMessage* message)
{
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_QOS && GST_MESSAGE_SRC(message) == GST_OBJECT(element)) {
        GstHandTracker* self = GST_HAND_TRACKER(element);
        self->stats->frame_skipped();
        guint64 timestamp = GST_CLOCK_TIME_NONE;
        gst_message_parse_qos(message, nullptr, nullptr, nullptr, &timestamp, nullptr);
        GST_DEBUG_OBJECT(self, "output frame %" GST_TIME_FORMAT " skipped under QoS", GST_TIME_ARGS(timestamp));
    }
    return GST_ELEMENT_CLASS(gst_hand_tracker_parent_class)->post_message(element, message);
}

// ---------------------------------------------------------------------------------------
// State

static gboolean gst_hand_tracker_start(GstAggregator* agg)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    const Settings settings = read_settings(self);
    // Load the calibration now so a bad file fails the state change with its reason.
    if (!build_tracker(self, settings)) return FALSE;
    self->rebuild->store(false);
    if (!prepare_head(self, settings) || !prepare_director(self, settings) || !open_json_output(self, settings))
        return FALSE;
    return GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->start(agg);
}

static gboolean gst_hand_tracker_stop(GstAggregator* agg)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    const gboolean ok = GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->stop(agg);
    TrackerState& e = *self->state;
    e.tracker.reset();
    e.head.reset();  // joins the head client's thread
    e.director.reset();
    close_json_output(self);
    e.forget();
    self->stats->reset();
    gst_aggregator_set_latency(agg, 0, 0);
    return ok;
}

// Any flush (a flushing seek through the element, or upstream flushing a pad) means the
// next frames do not follow the previous ones: tracking starts over.
static gboolean gst_hand_tracker_sink_event(GstAggregator* agg, GstAggregatorPad* pad, GstEvent* event)
{
    if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP) GST_HAND_TRACKER(agg)->flushed->store(true);
    return GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->sink_event(agg, pad, event);
}

// ---------------------------------------------------------------------------------------
// Properties

static void gst_hand_tracker_set_property(GObject* object, guint prop_id, const GValue* value, GParamSpec* pspec)
{
    GstHandTracker* self = GST_HAND_TRACKER(object);
    bool rebuild = false;
    GST_OBJECT_LOCK(self);
    const bool known = gc::gst::set_tracker_setting(*self->settings, prop_id, value, rebuild);
    GST_OBJECT_UNLOCK(self);
    if (!known) G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
    if (rebuild) self->rebuild->store(true);
}

static void gst_hand_tracker_get_property(GObject* object, guint prop_id, GValue* value, GParamSpec* pspec)
{
    GstHandTracker* self = GST_HAND_TRACKER(object);
    if (prop_id == gc::gst::kStatsProperty) {
        g_value_take_boxed(value, self->stats->to_structure());
        return;
    }
    GST_OBJECT_LOCK(self);
    const bool known = gc::gst::get_tracker_setting(*self->settings, prop_id, value);
    GST_OBJECT_UNLOCK(self);
    if (!known) G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
}

static void gst_hand_tracker_finalize(GObject* object)
{
    GstHandTracker* self = GST_HAND_TRACKER(object);
    delete self->state;
    delete self->settings;
    delete self->rebuild;
    delete self->flushed;
    delete self->stats;
    G_OBJECT_CLASS(gst_hand_tracker_parent_class)->finalize(object);
}

static void gst_hand_tracker_class_init(GstHandTrackerClass* klass)
{
    GObjectClass* gobject_class = G_OBJECT_CLASS(klass);
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);
    GstAggregatorClass* agg_class = GST_AGGREGATOR_CLASS(klass);
    GstVideoAggregatorClass* vagg_class = GST_VIDEO_AGGREGATOR_CLASS(klass);

    GST_DEBUG_CATEGORY_INIT(gst_hand_tracker_debug, "handtracker", 0, "stereo pointing-hand tracker");

    gobject_class->set_property = gst_hand_tracker_set_property;
    gobject_class->get_property = gst_hand_tracker_get_property;
    gobject_class->finalize = gst_hand_tracker_finalize;

    gc::gst::install_tracker_properties(gobject_class);
    element_class->post_message = gst_hand_tracker_post_message;

    add_tracker_pad_templates(element_class);

    gst_element_class_set_static_metadata(
        element_class, "Pointing hand tracker", "Filter/Analyzer/Video",
        "Tracks a pointing hand in the two views of a stereo camera (CONDENSATION particle filter), pairs the "
        "views by running time, computes the 3D pointing ray and outputs the left, right or attended view with "
        "GstHandPointingMeta. Request sink_left and sink_right, or sink for side-by-side frames",
        "GestureCAM <gesturecam@localhost>");

    agg_class->create_new_pad = gst_hand_tracker_create_new_pad;
    agg_class->sink_query = gst_hand_tracker_sink_query;
    agg_class->fixate_src_caps = gst_hand_tracker_fixate_src_caps;
    agg_class->start = gst_hand_tracker_start;
    agg_class->stop = gst_hand_tracker_stop;
    agg_class->sink_event = gst_hand_tracker_sink_event;
    vagg_class->aggregate_frames = gst_hand_tracker_aggregate_frames;

    gc::gst::mark_tracker_enums_as_plugin_api();
}

static void gst_hand_tracker_init(GstHandTracker* self)
{
    self->settings = new Settings();
    self->state = new TrackerState();
    self->rebuild = new std::atomic<bool>(false);
    self->flushed = new std::atomic<bool>(false);
    self->stats = new gc::gst::TrackerStats();
}
