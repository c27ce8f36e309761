#include "handtracker_tracking.hpp"

#include "handtracker_head.hpp"
#include "pointing_report.hpp"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>

#define GST_CAT_DEFAULT gst_hand_tracker_debug

namespace gc::gst {

using Settings = TrackerSettings;

Settings read_settings(GstHandTracker* self)
{
    GST_OBJECT_LOCK(self);
    Settings s = *self->settings;
    GST_OBJECT_UNLOCK(self);
    return s;
}

bool build_tracker(GstHandTracker* self, const Settings& settings)
{
    TrackerState& e = *self->state;
    try {
        if (settings.calibration != e.calibration_path) {
            e.calibration.reset();
            if (!settings.calibration.empty()) e.calibration = gc::load_calibration(settings.calibration);
            e.calibration_path = settings.calibration;
        }
    } catch (const std::exception& err) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                          ("Cannot use the calibration file \"%s\".", settings.calibration.c_str()),
                          ("%s", err.what()));
        return false;
    }
    gc::TrackerParams params;
    params.particles = settings.particles;
    params.tracking_width = settings.tracking_width;
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
    e.stream = {};
    return true;
}

// What a view's state change means to someone reading the log.
static const char* state_change(gc::TrackState from, gc::TrackState to)
{
    if (to == gc::TrackState::Tracking)
        return from == gc::TrackState::Lost ? "re-acquired the hand" : "acquired the hand";
    if (to == gc::TrackState::Lost) return "lost the hand";
    return "is looking for the hand";
}

void log_result(GstHandTracker* self, TrackerState& e, const gc::FrameResult& r)
{
    const std::array<const gc::EyeEstimate*, 2> eyes = {&r.left, &r.right};
    for (int i = 0; i < (r.stereo ? 2 : 1); ++i) {
        const gc::EyeEstimate& eye = *eyes[i];
        const char* name = i == 0 ? "left" : "right";
        if (eye.state != e.logged_state[i])
            GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s view %s (%s -> %s)", r.frame, name,
                            state_change(e.logged_state[i], eye.state), gc::to_string(e.logged_state[i]).data(),
                            gc::to_string(eye.state).data());
        if (eye.gesture != e.logged_gesture[i])
            GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s view gesture %s -> %s", r.frame, name,
                            gc::to_string(e.logged_gesture[i]).data(), gc::to_string(eye.gesture).data());
        e.logged_state[i] = eye.state;
        e.logged_gesture[i] = eye.gesture;
        GST_DEBUG_OBJECT(
            self, "frame %" G_GINT64_FORMAT ": %s view %s, confidence %.3f, fingertip (%.1f, %.1f), %.1f deg", r.frame,
            name, gc::to_string(eye.state).data(), eye.confidence, eye.fingertip.x, eye.fingertip.y, eye.pointing_deg);
    }
    if (r.pointing.valid)
        GST_DEBUG_OBJECT(self, "frame %" G_GINT64_FORMAT ": ray azimuth %.1f deg, elevation %.1f deg", r.frame,
                         r.pointing.azimuth_deg, r.pointing.elevation_deg);
    GST_LOG_OBJECT(self, "frame %" G_GINT64_FORMAT ": %s, fingertip (%.1f, %.1f), ray %s", r.frame,
                   gc::to_string(r.state).data(), r.left.fingertip.x, r.left.fingertip.y,
                   r.pointing.valid ? "yes" : "no");
}

GstFlowReturn track_views(GstHandTracker* self, const Settings& settings, const gc::gst::SlotViews& in, bool stereo,
                          GstVideoAggregatorPad* pose_pad, const GstVideoFrame* pose_frame, GstBuffer* outbuf)
{
    TrackerState& e = *self->state;
    const cv::Size size = in.views[0].size();
    if (!e.stream.view_size.empty() && (size != e.stream.view_size || stereo != e.stream.stereo)) {
        GST_INFO_OBJECT(self, "views changed to %dx%d: tracking starts over", size.width, size.height);
        e.tracker->reset();
        e.stream.attention.reset();
    }
    e.stream.view_size = size;
    e.stream.stereo = stereo;
    // The head's pose when these views were taken and the image motion it caused; without
    // a head: no pose, no motion.
    gc::headctl::HeadAtCapture at;
    if (const GstFlowReturn ret = head_at_capture(self, settings, size, pose_pad, pose_frame, outbuf, at);
        ret != GST_FLOW_OK)
        return ret;
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
        GST_ELEMENT_WARNING(
            self, STREAM, FAILED,
            ("Tracking failed on a frame (%" G_GUINT64_FORMAT " so far); the tracker starts over.", e.failed_frames),
            ("%s", err.what()));
    }
    return GST_FLOW_OK;
}

namespace {

// An `attended-target` element message: what the attended view frames from this frame on, so
// that an application (or a measurement) knows when a dwell ended.
void post_target(GstHandTracker* self, const char* event, const FrameResult& r, const std::optional<cv::Vec3d>& target)
{
    GstStructure* s = gst_structure_new("attended-target", "event", G_TYPE_STRING, event, "frame", G_TYPE_UINT64,
                                        guint64(std::max<std::int64_t>(r.frame, 0)), "timestamp", G_TYPE_UINT64,
                                        r.pts_ns >= 0 ? guint64(r.pts_ns) : GST_CLOCK_TIME_NONE, nullptr);
    if (target) set_vec3(s, "target-head-mm", *target);
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

}  // namespace

void pick_target(GstHandTracker* self, const TrackerSettings& settings, const FrameResult& r)
{
    TrackerState& e = *self->state;
    DwellParams params;
    params.dwell_s = settings.dwell_s;
    params.release_s = settings.dwell_s;
    params.target = settings.target;
    const double t_s = r.pts_ns >= 0 ? double(r.pts_ns) * 1e-9 : double(r.frame) / 30.0;
    const std::optional<cv::Vec3d> target = e.stream.dwell.update(t_s, r.pointing, params);
    const bool moved = target && e.stream.target && cv::norm(*target - *e.stream.target) > 1.0;
    if (target && (!e.stream.target || moved)) {
        GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": a held pointing picked a target at (%.0f, %.0f, %.0f) mm",
                        r.frame, (*target)[0], (*target)[1], (*target)[2]);
        post_target(self, "picked", r, target);
    } else if (!target && e.stream.target) {
        GST_INFO_OBJECT(self, "frame %" G_GINT64_FORMAT ": the target is released", r.frame);
        post_target(self, "released", r, std::nullopt);
    }
    e.stream.target = target;
}

}  // namespace gc::gst
