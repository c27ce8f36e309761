// handtracker: GObject glue over gc::PointingTracker. GstVideoAggregator pairs the views
// by running time and hands aggregate_frames() the prepared frame of every pad for one
// output slot; this file converts them to BGR, runs the shared tracker code path and
// publishes the result (meta, region of interest, bus message, optional JSON lines).
#include "gsthandtracker.hpp"

#include "attention_window.hpp"
#include "handtracker_settings.hpp"
#include "handtracker_views.hpp"
#include "head_connection.hpp"
#include "pointing_report.hpp"
#include "tracking_overlay.hpp"
#include "video_bgr.hpp"

#include "common/frame_limits.hpp"
#include "common/line_output.hpp"
#include "headctl/head_link.hpp"
#include "headctl/token.hpp"
#include "headctl/uri.hpp"
#include "stereo/calibration.hpp"
#include "tracker/pointing_tracker.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/video/gstvideometa.h>
#include <gst/video/video.h>
#include <opencv2/imgproc.hpp>

#include <array>
#include <atomic>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

GST_DEBUG_CATEGORY_STATIC(gst_hand_tracker_debug);
#define GST_CAT_DEFAULT gst_hand_tracker_debug

namespace {

using Settings = gc::gst::TrackerSettings;

// Everything the streaming thread owns.
struct Engine {
    std::unique_ptr<gc::PointingTracker> tracker;
    std::optional<gc::StereoCalibration> calibration;
    std::string calibration_path;  // the file `calibration` was loaded from
    cv::Size view_size;            // of the tracked views, to reset on renegotiation
    bool stereo = false;
    gc::gst::BgrReader readers[2];
    cv::Mat halves[2];             // the two views of a side-by-side frame
    cv::Mat canvas;                // the view being drawn on
    cv::Mat scaled;                // the view at the output size
    gc::gst::BgrWriter writer;
    std::vector<float> contour_scratch;
    gc::gst::AttentionWindow attention;
    gc::gst::TrackingOverlay overlay;
    std::optional<gc::LineOutput> json;  // json-location: one whole line per write, each checked
    std::string json_path;
    std::string json_line;
    std::optional<gc::TrackState> last_posted_state;
    std::unique_ptr<gc::HeadLink> head;
    std::string head_token;           // read from head-token-file at start
    cv::Size head_view_size;          // the view size of the head link's calibration
    bool warned_stale_views = false;  // the current run of too-old views was reported
    guint64 failed_frames = 0;        // frames the tracker failed on and that were passed on untracked
    // What the debug log last said of each view: a line is written when either changes.
    std::array<gc::TrackState, 2> logged_state = {gc::TrackState::Acquiring, gc::TrackState::Acquiring};
    std::array<gc::Gesture, 2> logged_gesture = {gc::Gesture::Unknown, gc::Gesture::Unknown};
    // The input timestamps of the views tracked last (packed or left, right).
    std::array<GstClockTime, 2> tracked_inputs = {GST_CLOCK_TIME_NONE, GST_CLOCK_TIME_NONE};

    void forget()
    {
        if (tracker)
            tracker->reset();
        attention.reset();
        view_size = {};
        last_posted_state.reset();
        tracked_inputs = {GST_CLOCK_TIME_NONE, GST_CLOCK_TIME_NONE};
    }
};

}  // namespace

struct _GstHandTracker {
    GstVideoAggregator parent;
    Settings* settings;
    Engine* engine;
    std::atomic<bool>* rebuild;  // tracker parameters changed
    std::atomic<bool>* flushed;  // a flushing seek: the frames jump
};

G_DEFINE_TYPE(GstHandTracker, gst_hand_tracker, GST_TYPE_VIDEO_AGGREGATOR)
GST_ELEMENT_REGISTER_DEFINE(handtracker, "handtracker", GST_RANK_NONE, GST_TYPE_HAND_TRACKER)

// The frame-size limit spelt out, as static caps need a literal.
static_assert(gc::kMaxFrameSide == 8192, "VIDEO_CAPS states gc::kMaxFrameSide");
#define VIDEO_CAPS(formats)                                                                        \
    "video/x-raw, format = (string) { " formats " }, width = (int) [ 32, 8192 ], "               \
    "height = (int) [ 32, 8192 ], framerate = (fraction) [ 0/1, 2147483647/1 ]"

static GstStaticPadTemplate sink_left_template =
    GST_STATIC_PAD_TEMPLATE("sink_left", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate sink_right_template =
    GST_STATIC_PAD_TEMPLATE("sink_right", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate sink_packed_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_REQUEST, GST_STATIC_CAPS(VIDEO_CAPS(GC_INPUT_FORMATS)));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS(GC_OUTPUT_FORMATS)));

static GstVideoAggregatorPad* sink_pad(GstHandTracker* self, const char* name)
{
    GstPad* pad = gst_element_get_static_pad(GST_ELEMENT(self), name);
    if (pad)
        gst_object_unref(pad);  // the element keeps its pads alive while streaming
    return pad ? GST_VIDEO_AGGREGATOR_PAD(pad) : nullptr;
}

// ---------------------------------------------------------------------------------------
// Pads

static GstAggregatorPad* gst_hand_tracker_create_new_pad(GstAggregator* agg, GstPadTemplate* templ,
                                                         const gchar* /*req_name*/, const GstCaps* /*caps*/)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    const gchar* name = GST_PAD_TEMPLATE_NAME_TEMPLATE(templ);
    GstElement* element = GST_ELEMENT(agg);
    if (GstPad* existing = gst_element_get_static_pad(element, name)) {
        gst_object_unref(existing);
        GST_WARNING_OBJECT(self, "pad %s already exists", name);
        return nullptr;
    }
    const bool packed = g_str_equal(name, "sink");
    const bool have_packed = sink_pad(self, "sink") != nullptr;
    const bool have_eyes = sink_pad(self, "sink_left") || sink_pad(self, "sink_right");
    if ((packed && have_eyes) || (!packed && have_packed)) {
        GST_WARNING_OBJECT(self, "pad %s cannot be combined with %s", name,
                           packed ? "sink_left/sink_right" : "the side-by-side pad sink");
        return nullptr;
    }
    return GST_AGGREGATOR_PAD(g_object_new(GST_PAD_TEMPLATE_GTYPE(templ), "name", name, "direction",
                                           GST_PAD_SINK, "template", templ, nullptr));
}

// Upstream reports refused caps only as not-negotiated: a frame size over the limit is named
// on the bus (a warning, since upstream may still choose smaller caps).
static void warn_if_too_large(GstHandTracker* self, GstPad* pad, GstCaps* caps)
{
    const GstStructure* s = gst_caps_is_fixed(caps) ? gst_caps_get_structure(caps, 0) : nullptr;
    int width = 0, height = 0;
    if (!s || !gst_structure_get_int(s, "width", &width) || !gst_structure_get_int(s, "height", &height) ||
        (width <= gc::kMaxFrameSide && height <= gc::kMaxFrameSide))
        return;
    GST_ELEMENT_WARNING(self, STREAM, FORMAT,
                        ("%s: frames of %dx%d are larger than the limit of %dx%d pixels.", GST_PAD_NAME(pad), width,
                         height, gc::kMaxFrameSide, gc::kMaxFrameSide),
                        ("the caps are refused"));
}

// Any size and format of the template on every sink pad, whatever downstream wants: the
// element converts itself, and a size mismatch between the views is reported in words
// when the frames meet instead of failing upstream's negotiation without a reason.
static gboolean gst_hand_tracker_sink_query(GstAggregator* agg, GstAggregatorPad* pad, GstQuery* query)
{
    switch (GST_QUERY_TYPE(query)) {
    case GST_QUERY_CAPS: {
        GstCaps* filter = nullptr;
        gst_query_parse_caps(query, &filter);
        GstCaps* caps = gst_pad_get_pad_template_caps(GST_PAD(pad));
        if (filter) {
            GstCaps* both = gst_caps_intersect_full(filter, caps, GST_CAPS_INTERSECT_FIRST);
            gst_caps_unref(caps);
            caps = both;
        }
        gst_query_set_caps_result(query, caps);
        gst_caps_unref(caps);
        return TRUE;
    }
    case GST_QUERY_ACCEPT_CAPS: {
        GstCaps* caps = nullptr;
        gst_query_parse_accept_caps(query, &caps);
        GstCaps* templ = gst_pad_get_pad_template_caps(GST_PAD(pad));
        const gboolean accepted = gst_caps_is_subset(caps, templ);
        gst_caps_unref(templ);
        if (!accepted)
            warn_if_too_large(GST_HAND_TRACKER(agg), GST_PAD(pad), caps);
        gst_query_set_accept_caps_result(query, accepted);
        return TRUE;
    }
    default:
        return GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->sink_query(agg, pad, query);
    }
}

// The size of one view as the pads currently describe it.
static bool current_view_size(GstHandTracker* self, int& width, int& height)
{
    for (const char* name : {"sink_left", "sink_right", "sink"}) {
        GstVideoAggregatorPad* pad = sink_pad(self, name);
        if (!pad)
            continue;
        GST_OBJECT_LOCK(self);
        GstVideoInfo info = pad->info;
        GST_OBJECT_UNLOCK(self);
        if (!info.finfo || GST_VIDEO_INFO_FORMAT(&info) == GST_VIDEO_FORMAT_UNKNOWN || info.width == 0)
            continue;
        width = info.width;
        height = info.height;
        if (g_str_equal(name, "sink")) {
            if (GST_VIDEO_INFO_MULTIVIEW_MODE(&info) == GST_VIDEO_MULTIVIEW_MODE_TOP_BOTTOM)
                height /= 2;
            else
                width /= 2;
        }
        return true;
    }
    return false;
}

// The output follows the size of one view unless downstream asks for another.
static GstCaps* gst_hand_tracker_fixate_src_caps(GstAggregator* agg, GstCaps* caps)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    int width = 640, height = 480;
    current_view_size(self, width, height);
    gint fps_n = 30, fps_d = 1;
    for (const char* name : {"sink_left", "sink_right", "sink"}) {
        GstVideoAggregatorPad* pad = sink_pad(self, name);
        if (pad && pad->info.finfo && GST_VIDEO_INFO_FPS_N(&pad->info) > 0) {
            fps_n = GST_VIDEO_INFO_FPS_N(&pad->info);
            fps_d = GST_VIDEO_INFO_FPS_D(&pad->info);
            break;
        }
    }
    caps = gst_caps_make_writable(caps);
    GstStructure* s = gst_caps_get_structure(caps, 0);
    gst_structure_fixate_field_nearest_int(s, "width", width);
    gst_structure_fixate_field_nearest_int(s, "height", height);
    gst_structure_fixate_field_nearest_fraction(s, "framerate", fps_n, fps_d);
    if (gst_structure_has_field(s, "pixel-aspect-ratio"))
        gst_structure_fixate_field_nearest_fraction(s, "pixel-aspect-ratio", 1, 1);
    return gst_caps_fixate(caps);
}

// ---------------------------------------------------------------------------------------
// Tracking

static Settings read_settings(GstHandTracker* self)
{
    GST_OBJECT_LOCK(self);
    Settings s = *self->settings;
    GST_OBJECT_UNLOCK(self);
    return s;
}

// (Re)creates the tracker from the settings; loads the calibration file when it changed.
// Posts an error and returns false when the file cannot be used.
static bool build_tracker(GstHandTracker* self, const Settings& settings)
{
    Engine& e = *self->engine;
    try {
        if (settings.calibration != e.calibration_path) {
            e.calibration.reset();
            if (!settings.calibration.empty())
                e.calibration = gc::load_calibration(settings.calibration);
            e.calibration_path = settings.calibration;
        }
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("Cannot use the calibration file \"%s\".", settings.calibration.c_str()),
                          ("%s", err.what()));
        return false;
    }
    gc::TrackerParams params;
    params.particles = settings.particles;
    params.seed = settings.seed;
    params.lost_ratio = settings.lost_threshold;
    params.lost_frames = settings.lost_frames;
    params.detector = settings.detector;
    params.model_dir = settings.model_dir;
    try {
        e.tracker = std::make_unique<gc::PointingTracker>(params, e.calibration);
    } catch (const std::runtime_error& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, NOT_FOUND, ("Cannot load the learned hand models."),
                          ("%s (set model-dir, or detector=motion to track without them)", err.what()));
        return false;
    }
    e.attention.reset();
    e.view_size = {};
    e.tracked_inputs = {GST_CLOCK_TIME_NONE, GST_CLOCK_TIME_NONE};
    e.last_posted_state.reset();
    return true;
}

static bool views_ready(const GstVideoFrame* frame) { return frame && frame->buffer; }

// Logs each view's acquisition, loss, re-acquisition and gesture changes (INFO), and every
// tracked frame's summary (LOG).
static void log_result(GstHandTracker* self, Engine& e, const gc::FrameResult& r)
{
    const std::array<const gc::EyeEstimate*, 2> eyes = {&r.left, &r.right};
    for (int i = 0; i < (r.stereo ? 2 : 1); ++i) {
        const gc::EyeEstimate& eye = *eyes[i];
        const char* name = i == 0 ? "left" : "right";
        if (eye.state != e.logged_state[i])
            GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s view %s -> %s", r.frame, name,
                            gc::to_string(e.logged_state[i]).data(), gc::to_string(eye.state).data());
        if (eye.gesture != e.logged_gesture[i])
            GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s view gesture %s", r.frame, name,
                            gc::to_string(eye.gesture).data());
        e.logged_state[i] = eye.state;
        e.logged_gesture[i] = eye.gesture;
    }
    GST_LOG_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s, fingertip (%.1f, %.1f), ray %s", r.frame,
                   gc::to_string(r.state).data(), r.left.fingertip.x, r.left.fingertip.y,
                   r.pointing.valid ? "yes" : "no");
}

static bool should_post(Engine& e, GstHandTrackerMessageUpdates mode, gc::TrackState state)
{
    switch (mode) {
    case GST_HAND_TRACKER_MESSAGES_NONE:
        return false;
    case GST_HAND_TRACKER_MESSAGES_ON_CHANGE:
        if (e.last_posted_state == state)
            return false;
        break;
    case GST_HAND_TRACKER_MESSAGES_EVERY_FRAME:
        break;
    }
    e.last_posted_state = state;
    return true;
}

// The running time and stream time of an output timestamp.
static void output_times(GstHandTracker* self, GstClockTime pts, GstClockTime& running, GstClockTime& stream)
{
    GstAggregator* agg = GST_AGGREGATOR(self);
    GST_OBJECT_LOCK(agg->srcpad);
    const GstSegment* segment = &GST_AGGREGATOR_PAD(agg->srcpad)->segment;
    running = gst_segment_to_running_time(segment, GST_FORMAT_TIME, pts);
    stream = gst_segment_to_stream_time(segment, GST_FORMAT_TIME, pts);
    GST_OBJECT_UNLOCK(agg->srcpad);
}

// The running time of a pad's prepared frame (NONE if it has no timestamp).
static GstClockTime input_running_time(GstVideoAggregatorPad* pad, const GstVideoFrame* frame)
{
    if (!pad || !views_ready(frame) || !GST_BUFFER_PTS_IS_VALID(frame->buffer))
        return GST_CLOCK_TIME_NONE;
    GstAggregatorPad* apad = GST_AGGREGATOR_PAD(pad);
    GST_OBJECT_LOCK(apad);
    const GstClockTime running = gst_segment_to_running_time(&apad->segment, GST_FORMAT_TIME, GST_BUFFER_PTS(frame->buffer));
    GST_OBJECT_UNLOCK(apad);
    return running;
}

static void post_message(GstHandTracker* self, GstBuffer* outbuf, const gc::FrameResult& result,
                         const gc::gst::ReportContext& context)
{
    GstStructure* s = gc::gst::pointing_structure(result, context, true);
    const GstClockTime pts = GST_BUFFER_PTS(outbuf);
    GstClockTime running = GST_CLOCK_TIME_NONE, stream = GST_CLOCK_TIME_NONE;
    output_times(self, pts, running, stream);
    gst_structure_set(s, "timestamp", G_TYPE_UINT64, pts, "running-time", G_TYPE_UINT64, running, "stream-time",
                      G_TYPE_UINT64, stream, "duration", G_TYPE_UINT64, GST_BUFFER_DURATION(outbuf), nullptr);
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

// The region of interest in the output buffer's pixels: the output view's hand box mapped
// through the crop and the scaling.
static void add_region_of_interest(GstBuffer* outbuf, const gc::FrameResult& result, bool right_view,
                                   const cv::Rect& view, cv::Size out, const gc::gst::ReportContext& context)
{
    const gc::EyeEstimate& eye = right_view ? result.right : result.left;
    if (eye.state == gc::TrackState::Acquiring || eye.bbox.area() <= 0 || view.area() <= 0)
        return;
    const double sx = double(out.width) / view.width;
    const double sy = double(out.height) / view.height;
    cv::Rect box(int((eye.bbox.x - view.x) * sx), int((eye.bbox.y - view.y) * sy), int(eye.bbox.width * sx),
                 int(eye.bbox.height * sy));
    box &= cv::Rect(0, 0, out.width, out.height);
    if (box.area() <= 0)
        return;
    GstVideoRegionOfInterestMeta* roi =
        gst_buffer_add_video_region_of_interest_meta(outbuf, "hand", guint(box.x), guint(box.y), guint(box.width),
                                                     guint(box.height));
    gst_video_region_of_interest_meta_add_param(roi, gc::gst::pointing_structure(result, context, false));
}

static GstFlowReturn size_mismatch(GstHandTracker* self, const GstVideoFrame* left, const GstVideoFrame* right)
{
    GST_ELEMENT_ERROR(self, CORE, NEGOTIATION,
                      ("sink_left is %dx%d but sink_right is %dx%d", GST_VIDEO_FRAME_WIDTH(left),
                       GST_VIDEO_FRAME_HEIGHT(left), GST_VIDEO_FRAME_WIDTH(right), GST_VIDEO_FRAME_HEIGHT(right)),
                      ("the two views of a stereo pair must have the same size"));
    return GST_FLOW_NOT_NEGOTIATED;
}

// The head link for views of `size`, (re)built when there is none yet or when, without a
// calibration file, the views changed size (the nominal rig depends on it). Connecting
// happens on the link's own thread.
static bool ensure_head_link(GstHandTracker* self, const Settings& settings, cv::Size size)
{
    Engine& e = *self->engine;
    if (e.head && (e.calibration || size == e.head_view_size))
        return true;
    e.head.reset();
    gc::HeadLinkConfig config;
    config.uri = settings.head;
    config.token = e.head_token;
    config.steer = settings.steer;
    config.target_distance_mm = settings.target_distance_mm;
    config.clock = gc::gst::element_clock(GST_ELEMENT(self));
    config.on_state_change = gc::gst::connection_reporter(GST_ELEMENT(self), settings.head);
    // Only live views have an age: recorded ones are taken at their stream time, however
    // fast or slow they are read.
    if (!GST_CLOCK_TIME_IS_VALID(gst_aggregator_get_latency(GST_AGGREGATOR(self))))
        config.max_view_age = std::chrono::hours(24 * 365);
    try {
        e.head = std::make_unique<gc::HeadLink>(std::move(config),
                                                e.calibration ? *e.calibration : gc::default_calibration(size));
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                          ("Cannot use the head at \"%s\".", gc::headctl::redact_uri(settings.head).c_str()),
                          ("%s", err.what()));
        return false;
    }
    e.head_view_size = size;
    return true;
}

// Runs the tracker on the slot's views (`pose_pad`/`pose_frame` give their capture time for
// the head's pose), with the head's motion when there is a head.
static GstFlowReturn track_views(GstHandTracker* self, const Settings& settings, const gc::gst::SlotViews& in,
                                 bool stereo, GstVideoAggregatorPad* pose_pad, const GstVideoFrame* pose_frame,
                                 GstBuffer* outbuf)
{
    Engine& e = *self->engine;
    const cv::Size size = in.views[0].size();
    if (!e.view_size.empty() && (size != e.view_size || stereo != e.stereo)) {
        GST_INFO_OBJECT(self, "views changed to %dx%d: tracking starts over", size.width, size.height);
        e.tracker->reset();
        e.attention.reset();
    }
    e.view_size = size;
    e.stereo = stereo;
    // The head's pose when these views were taken and the image motion it caused; without
    // a head: no pose, no motion.
    gc::HeadAtCapture at;
    if (!settings.head.empty()) {
        if (!ensure_head_link(self, settings, size))
            return GST_FLOW_ERROR;
        e.head->set_steering(settings.steer, settings.target_distance_mm);
        // The views' own running time, not the output slot's: a live source that started
        // late, or a pad that is behind, gives the slot older views, and the pose must be
        // the one they were taken at.
        const GstClockTime running = input_running_time(pose_pad, pose_frame);
        GST_LOG_OBJECT(self, "views at running time %" GST_TIME_FORMAT " for output %" GST_TIME_FORMAT,
                       GST_TIME_ARGS(running), GST_TIME_ARGS(GST_BUFFER_PTS(outbuf)));
        at = e.head->begin_frame(gc::gst::capture_time(GST_ELEMENT(self), running));
    }
    try {
        const gint64 pts = GST_CLOCK_TIME_IS_VALID(GST_BUFFER_PTS(outbuf)) ? gint64(GST_BUFFER_PTS(outbuf)) : -1;
        if (stereo)
            e.tracker->process_stereo(in.views[0], in.views[1], pts, at.pose, at.left_motion, at.right_motion);
        else
            e.tracker->process_mono(in.views[0], pts, at.left_motion);
    } catch (const gc::CalibrationError& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("The calibration does not fit the stream."), ("%s", err.what()));
        return GST_FLOW_ERROR;
    } catch (const std::invalid_argument& err) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("%s", err.what()), (nullptr));
        return GST_FLOW_NOT_NEGOTIATED;
    } catch (const std::exception& err) {
        // One bad frame must not end the stream: the tracker starts over and the frame goes
        // on untracked.
        e.tracker->reset();
        ++e.failed_frames;
        GST_ELEMENT_WARNING(self, STREAM, FAILED,
                            ("Tracking failed on a frame (%" G_GUINT64_FORMAT " so far); the tracker starts over.",
                             e.failed_frames),
                            ("%s", err.what()));
    }
    return GST_FLOW_OK;
}

// Hands a tracked frame's result to the head link, warning once per episode when the views
// come too late to steer from (the head then holds).
static void steer_head(GstHandTracker* self, const Settings& settings, const gc::FrameResult& result)
{
    Engine& e = *self->engine;
    e.head->end_frame(result);  // never waits: the command goes to the link's thread
    const bool stale = settings.steer != gc::SteerMode::Off && e.head->last_view_stale();
    if (stale && !e.warned_stale_views)
        GST_ELEMENT_WARNING(self, STREAM, FAILED,
                            ("Views reach the tracker %.0f ms after capture: the head is not steered from "
                             "them until the pipeline keeps up.",
                             e.head->last_view_age_ms()),
                            ("The machine may be too slow for this frame rate, or an element upstream "
                             "queues frames."));
    e.warned_stale_views = stale;
}

// Writes the output view into `outbuf`; `context` receives what it shows.
static GstFlowReturn compose_output(GstHandTracker* self, const Settings& settings, GstBuffer* outbuf,
                                    const gc::gst::SlotViews& in, bool stereo, bool complete, int& shown,
                                    gc::gst::ReportContext& context)
{
    Engine& e = *self->engine;
    const gc::FrameResult& result = e.tracker->last();
    GstVideoFrame out;
    if (!gst_video_frame_map(&out, &GST_VIDEO_AGGREGATOR(self)->info, outbuf, GST_MAP_WRITE)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot map the output buffer."), (nullptr));
        return GST_FLOW_ERROR;
    }
    const cv::Size out_size(GST_VIDEO_FRAME_WIDTH(&out), GST_VIDEO_FRAME_HEIGHT(&out));
    shown = settings.output == GST_HAND_TRACKER_OUTPUT_RIGHT && stereo ? 1 : 0;
    if (!in.have[shown])
        shown = in.have[0] ? 0 : 1;  // an incomplete pair shows the view that is there
    gc::gst::ViewChoice choice;
    choice.shown = shown;
    choice.draw = settings.draw;
    choice.attended = settings.output == GST_HAND_TRACKER_OUTPUT_ATTENDED && shown == 0 && in.have[0];
    context.incomplete = !complete;
    context.full_view = !choice.attended;
    std::span<const gc::Particle> particles;
    if (settings.draw && complete)
        particles = e.tracker->particles(shown == 1 ? gc::Eye::Right : gc::Eye::Left);
    try {
        context.view = gc::gst::compose_view(in, choice, result, particles, out_size, e.attention, e.overlay,
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

// The result on the buffer (meta, region of interest), on the bus, and in the JSON lines.
static GstFlowReturn publish(GstHandTracker* self, const Settings& settings, GstBuffer* outbuf, bool tracked,
                             int shown, const gc::gst::ReportContext& context)
{
    Engine& e = *self->engine;
    const gc::FrameResult& result = e.tracker->last();
    const cv::Size out_size(GST_VIDEO_INFO_WIDTH(&GST_VIDEO_AGGREGATOR(self)->info),
                            GST_VIDEO_INFO_HEIGHT(&GST_VIDEO_AGGREGATOR(self)->info));
    if (GstHandPointingMeta* meta = gst_buffer_add_hand_pointing_meta(outbuf))
        gc::gst::fill_meta(*meta, result, context, e.contour_scratch);
    add_region_of_interest(outbuf, result, shown == 1, context.view, out_size, context);
    if (should_post(e, settings.message_updates, result.state))
        post_message(self, outbuf, result, context);
    if (!tracked || !e.json)
        return GST_FLOW_OK;
    e.json_line = gc::to_json_line(result);
    e.json_line += '\n';
    try {
        e.json->write_line(e.json_line);
    } catch (const gc::OutputError& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, WRITE, ("Cannot write to \"%s\".", e.json_path.c_str()), ("%s", err.what()));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

static GstFlowReturn gst_hand_tracker_aggregate_frames(GstVideoAggregator* vagg, GstBuffer* outbuf)
{
    GstHandTracker* self = GST_HAND_TRACKER(vagg);
    Engine& e = *self->engine;
    const Settings settings = read_settings(self);
    if (self->rebuild->exchange(false) || !e.tracker) {
        if (!build_tracker(self, settings))
            return GST_FLOW_ERROR;
    }
    if (self->flushed->exchange(false))
        e.forget();

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
        gc::gst::read_views(e.readers, e.halves, packed_pad ? packed : nullptr, left, right, in);
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, STREAM, FORMAT, ("Cannot read an input frame."), ("%s", err.what()));
        return GST_FLOW_ERROR;
    }

    // Track when the pair is complete (mono: the left view alone) and not the pair tracked
    // last time: a live aggregator repeats its pads' last frames when a source is late or
    // at EOS, and a frame tracked twice would count as a hand that stood still.
    const bool complete = stereo ? (in.have[0] && in.have[1]) : in.have[0];
    auto pts_of = [](const GstVideoFrame* f) { return views_ready(f) ? GST_BUFFER_PTS(f->buffer) : GST_CLOCK_TIME_NONE; };
    const std::array<GstClockTime, 2> inputs = {pts_of(packed_pad ? packed : left),
                                                packed_pad ? GST_CLOCK_TIME_NONE : pts_of(right)};
    const bool repeated = complete && e.tracked_inputs == inputs && GST_CLOCK_TIME_IS_VALID(inputs[0]);
    const bool tracked = complete && !repeated;
    if (tracked) {
        e.tracked_inputs = inputs;
        const GstFlowReturn ret = track_views(self, settings, in, stereo, packed_pad ? packed_pad : left_pad,
                                              packed_pad ? packed : left, outbuf);
        if (ret != GST_FLOW_OK)
            return ret;
        log_result(self, e, e.tracker->last());
        if (e.head)
            steer_head(self, settings, e.tracker->last());
    }
    int shown = 0;
    gc::gst::ReportContext context;
    const GstFlowReturn ret = compose_output(self, settings, outbuf, in, stereo, complete, shown, context);
    if (ret != GST_FLOW_OK)
        return ret;
    return publish(self, settings, outbuf, tracked, shown, context);
}

// ---------------------------------------------------------------------------------------
// State

static gboolean gst_hand_tracker_start(GstAggregator* agg)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    const Settings settings = read_settings(self);
    // Load the calibration now so a bad file fails the state change with its reason.
    if (!build_tracker(self, settings))
        return FALSE;
    self->rebuild->store(false);
    Engine& e = *self->engine;
    e.head.reset();
    if (!settings.head.empty()) {
        try {
            gc::headctl::parse_head_uri(settings.head);
        } catch (const std::exception& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                              ("Invalid head URI \"%s\".", gc::headctl::redact_uri(settings.head).c_str()),
                              ("%s", err.what()));
            return FALSE;
        }
    }
    e.head_token.clear();
    if (!settings.head_token_file.empty()) {
        try {
            e.head_token = gc::headctl::read_token_file(settings.head_token_file);
        } catch (const std::exception& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, OPEN_READ,
                              ("Cannot read the head token file \"%s\".", settings.head_token_file.c_str()),
                              ("%s", err.what()));
            return FALSE;
        }
    }
    e.json.reset();
    e.json_path = settings.json_location;
    if (!settings.json_location.empty()) {
        try {
            e.json = gc::LineOutput::create(settings.json_location);
        } catch (const gc::OutputError& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE, ("Cannot open \"%s\" for writing.", e.json_path.c_str()),
                              ("%s", err.what()));
            return FALSE;
        }
    }
    return GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->start(agg);
}

static gboolean gst_hand_tracker_stop(GstAggregator* agg)
{
    GstHandTracker* self = GST_HAND_TRACKER(agg);
    const gboolean ok = GST_AGGREGATOR_CLASS(gst_hand_tracker_parent_class)->stop(agg);
    Engine& e = *self->engine;
    e.tracker.reset();
    e.head.reset();  // joins the head client's thread
    if (e.json) {
        try {
            e.json->close();
        } catch (const gc::OutputError& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, CLOSE, ("Cannot close \"%s\".", e.json_path.c_str()), ("%s", err.what()));
        }
        e.json.reset();
    }
    e.attention.reset();
    e.view_size = {};
    e.tracked_inputs = {GST_CLOCK_TIME_NONE, GST_CLOCK_TIME_NONE};
    e.last_posted_state.reset();
    return ok;
}

// Any flush (a flushing seek through the element, or upstream flushing a pad) means the
// next frames do not follow the previous ones: tracking starts over.
static gboolean gst_hand_tracker_sink_event(GstAggregator* agg, GstAggregatorPad* pad, GstEvent* event)
{
    if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP)
        GST_HAND_TRACKER(agg)->flushed->store(true);
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
    if (!known)
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
    if (rebuild)
        self->rebuild->store(true);
}

static void gst_hand_tracker_get_property(GObject* object, guint prop_id, GValue* value, GParamSpec* pspec)
{
    GstHandTracker* self = GST_HAND_TRACKER(object);
    GST_OBJECT_LOCK(self);
    const bool known = gc::gst::get_tracker_setting(*self->settings, prop_id, value);
    GST_OBJECT_UNLOCK(self);
    if (!known)
        G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
}

static void gst_hand_tracker_finalize(GObject* object)
{
    GstHandTracker* self = GST_HAND_TRACKER(object);
    delete self->engine;
    delete self->settings;
    delete self->rebuild;
    delete self->flushed;
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

    gst_element_class_add_static_pad_template_with_gtype(element_class, &sink_left_template,
                                                         GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(element_class, &sink_right_template,
                                                         GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(element_class, &sink_packed_template,
                                                         GST_TYPE_VIDEO_AGGREGATOR_PAD);
    gst_element_class_add_static_pad_template_with_gtype(element_class, &src_template, GST_TYPE_AGGREGATOR_PAD);

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
    self->engine = new Engine();
    self->rebuild = new std::atomic<bool>(false);
    self->flushed = new std::atomic<bool>(false);
}
