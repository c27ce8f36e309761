#include "handtracker_head.hpp"

#include "handtracker_views.hpp"
#include "head_connection.hpp"
#include "head_uri_property.hpp"

#include "headctl/uri.hpp"

#include <chrono>
#include <exception>
#include <memory>

#define GST_CAT_DEFAULT gst_hand_tracker_debug

namespace gc::gst {

namespace {

using Settings = TrackerSettings;

// The running time of a pad's prepared frame (NONE if it has no timestamp).
GstClockTime input_running_time(GstVideoAggregatorPad* pad, const GstVideoFrame* frame)
{
    if (!pad || !views_ready(frame) || !GST_BUFFER_PTS_IS_VALID(frame->buffer)) return GST_CLOCK_TIME_NONE;
    GstAggregatorPad* apad = GST_AGGREGATOR_PAD(pad);
    GST_OBJECT_LOCK(apad);
    const GstClockTime running =
        gst_segment_to_running_time(&apad->segment, GST_FORMAT_TIME, GST_BUFFER_PTS(frame->buffer));
    GST_OBJECT_UNLOCK(apad);
    return running;
}

gc::headctl::SteeringTimes steering_times(const Settings& settings)
{
    gc::headctl::SteeringTimes times;
    times.dwell_s = settings.dwell_s;
    times.look_s = settings.look_s;
    times.manual_pause_s = settings.manual_pause_s;
    return times;
}

// The head link for views of `size`, (re)built when there is none yet or when, without a
// calibration file, the views changed size (the nominal rig depends on it). Connecting
// happens on the link's own thread.
bool ensure_head_link(GstHandTracker* self, const Settings& settings, cv::Size size)
{
    TrackerState& e = *self->state;
    if (e.head && (e.calibration || size == e.head_view_size)) return true;
    e.head.reset();
    gc::headctl::HeadLinkConfig config;
    config.uri = settings.head;
    config.token = e.head_token;
    config.steer = settings.steer;
    config.target = settings.target;
    if (settings.home_preset >= 0) config.fixate.home_preset = settings.home_preset;
    config.fixate.widen_after_s = settings.widen_after_s;
    config.fixate.hold_s = settings.home_after_s;
    config.clock = gc::gst::element_clock(GST_ELEMENT(self));
    config.on_state_change = gc::gst::connection_reporter(GST_ELEMENT(self), settings.head);
    config.on_command = gc::gst::command_logger(GST_ELEMENT(self));
    config.on_steering = gc::gst::steering_reporter(GST_ELEMENT(self));
    config.times = steering_times(settings);
    // Only live views have an age: recorded ones are taken at their stream time, however
    // fast or slow they are read.
    if (!GST_CLOCK_TIME_IS_VALID(gst_aggregator_get_latency(GST_AGGREGATOR(self))))
        config.max_view_age = std::chrono::hours(24 * 365);
    try {
        e.head = std::make_unique<gc::headctl::HeadLink>(
            std::move(config), e.calibration ? *e.calibration : gc::default_calibration(size));
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                          ("Cannot use the head at \"%s\".", gc::headctl::redact_uri(settings.head).c_str()),
                          ("%s", err.what()));
        return false;
    }
    e.head_view_size = size;
    return true;
}

}  // namespace

bool prepare_head(GstHandTracker* self, const Settings& settings)
{
    TrackerState& e = *self->state;
    e.head.reset();
    if (!settings.head.empty()) {
        try {
            gc::headctl::parse_head_uri(settings.head);
        } catch (const std::exception& err) {
            GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                              ("Invalid head URI \"%s\".", gc::headctl::redact_uri(settings.head).c_str()),
                              ("%s", err.what()));
            return false;
        }
    }
    return read_head_token(GST_ELEMENT(self), settings.head_token_file, e.head_token);
}

GstFlowReturn head_at_capture(GstHandTracker* self, const Settings& settings, cv::Size size,
                              GstVideoAggregatorPad* pose_pad, const GstVideoFrame* pose_frame, GstBuffer* outbuf,
                              headctl::HeadAtCapture& at)
{
    TrackerState& e = *self->state;
    if (settings.head.empty()) return GST_FLOW_OK;
    if (!ensure_head_link(self, settings, size)) return GST_FLOW_ERROR;
    e.head->set_steering(settings.steer, settings.target);
    e.head->set_times(steering_times(settings));
    // The views' own running time, not the output slot's: a live source that started
    // late, or a pad that is behind, gives the slot older views, and the pose must be
    // the one they were taken at.
    const GstClockTime running = input_running_time(pose_pad, pose_frame);
    GST_LOG_OBJECT(self, "views at running time %" GST_TIME_FORMAT " for output %" GST_TIME_FORMAT,
                   GST_TIME_ARGS(running), GST_TIME_ARGS(GST_BUFFER_PTS(outbuf)));
    at = e.head->begin_frame(gc::gst::capture_time(GST_ELEMENT(self), running));
    if (at.pose)
        GST_LOG_OBJECT(self, "head at capture: pan %.2f tilt %.2f deg; left view moved %.1f, %.1f px", at.pose->pan_deg,
                       at.pose->tilt_deg, at.left_motion.dx, at.left_motion.dy);
    return GST_FLOW_OK;
}

void steer_head(GstHandTracker* self, const Settings& settings, const gc::FrameResult& result)
{
    TrackerState& e = *self->state;
    e.head->end_frame(result);  // never waits: the command goes to the link's thread
    const bool stale = settings.steer != gc::headctl::SteerMode::Off && e.head->last_view_stale();
    if (stale && !e.warned_stale_views)
        GST_ELEMENT_WARNING(self, STREAM, FAILED,
                            ("Views reach the tracker %.0f ms after capture: the head is not steered from "
                             "them until the pipeline keeps up.",
                             e.head->last_view_age_ms()),
                            ("The machine may be too slow for this frame rate, or an element upstream "
                             "queues frames."));
    e.warned_stale_views = stale;
}

}  // namespace gc::gst
