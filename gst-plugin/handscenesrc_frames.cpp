#include "handscenesrc_frames.hpp"

#include "head_connection.hpp"
#include "pointing_report.hpp"
#include "video_bgr.hpp"

#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#define GST_CAT_DEFAULT gst_hand_scene_src_debug

namespace gc::gst {

HeadPose pose_at_capture(GstHandSceneSrc* self, const SceneSettings& settings, GstClockTime pts)
{
    const SceneState& st = *self->state;
    // The head's pose when this frame is exposed (its running time is its timestamp): a
    // live frame is rendered at that moment, so the pose is extrapolated from the head's
    // last report (at most one status interval old) along its velocity. Home until the
    // head is first heard from; its last pose while it is away. Without a head: the rig's.
    gc::HeadPose pose = st.head ? st.stream.pose : settings.rig;
    if (st.head) {
        const GstClockTime running = gst_segment_to_running_time(&GST_BASE_SRC(self)->segment, GST_FORMAT_TIME, pts);
        if (std::optional<gc::HeadPose> at = st.head->pose_at(gc::gst::capture_time(GST_ELEMENT(self), running)))
            pose = *at;
        GST_LOG_OBJECT(self, "frame at running time %" GST_TIME_FORMAT " from the head's pose pan %.2f tilt %.2f deg",
                       GST_TIME_ARGS(running), pose.pan_deg, pose.tilt_deg);
    }
    return pose;
}

GstFlowReturn render_frame(GstHandSceneSrc* self, const SceneSettings& settings, guint64 frame, const HeadPose& pose,
                           GstBuffer* buffer)
{
    SceneState& st = *self->state;
    GstVideoFrame out;
    if (!gst_video_frame_map(&out, &st.stream.info, buffer, GST_MAP_WRITE)) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot map the output buffer."), (nullptr));
        return GST_FLOW_ERROR;
    }
    try {
        gc::sim::EyeTruth* truth = settings.truth_messages ? &st.truth : nullptr;
        // A head turned further than the simulated room reaches (one wall ahead): keep the
        // last pose that could be shown rather than stopping the stream.
        try {
            st.scene->render(int(frame), settings.eye, pose, st.bgr, truth);
            st.stream.pose = pose;
        } catch (const std::invalid_argument& err) {
            if (!st.stream.warned_pose)
                GST_ELEMENT_WARNING(self, STREAM, FAILED,
                                    ("The head turned past what the simulated room can show; rendering from "
                                     "the last pose it could."),
                                    ("%s", err.what()));
            st.stream.warned_pose = true;
            st.scene->render(int(frame), settings.eye, st.stream.pose, st.bgr, truth);
        }
        st.writer.write(st.bgr, out);
    } catch (const std::exception& err) {
        gst_video_frame_unmap(&out);
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Cannot render frame %" G_GUINT64_FORMAT ".", frame),
                          ("%s", err.what()));
        return GST_FLOW_ERROR;
    }
    gst_video_frame_unmap(&out);
    return GST_FLOW_OK;
}

void post_truth(GstHandSceneSrc* self, guint64 frame, GstClockTime pts, const SceneSettings& settings)
{
    const gc::sim::Scene& scene = *self->state->scene;
    const gc::sim::EyeTruth& t = self->state->truth;
    const gc::sim::HandTruth hand = scene.hand_truth(scene.hand_pose(int(frame)));
    GstStructure* s = gst_structure_new(
        "hand-truth", "frame", G_TYPE_UINT64, frame, "timestamp", G_TYPE_UINT64, pts, "eye", G_TYPE_STRING,
        settings.eye == gc::Eye::Left ? "left" : "right", "visible", G_TYPE_BOOLEAN, gboolean(t.visible), "palm-x",
        G_TYPE_DOUBLE, t.palm_px.x, "palm-y", G_TYPE_DOUBLE, t.palm_px.y, "fingertip-x", G_TYPE_DOUBLE,
        t.fingertip_px.x, "fingertip-y", G_TYPE_DOUBLE, t.fingertip_px.y, "pointing-deg", G_TYPE_DOUBLE, t.pointing_deg,
        "bbox-x", G_TYPE_INT, t.bbox.x, "bbox-y", G_TYPE_INT, t.bbox.y, "bbox-width", G_TYPE_INT, t.bbox.width,
        "bbox-height", G_TYPE_INT, t.bbox.height, "gesture", G_TYPE_STRING,
        std::string(to_string(hand.gesture)).c_str(), nullptr);
    gc::gst::set_vec3(s, "fingertip-head-mm", hand.fingertip_mm);
    gc::gst::set_vec3(s, "palm-head-mm", hand.palm_mm);
    gc::gst::set_vec3(s, "direction-head", hand.direction);
    const gc::HeadPose& pose = self->state->stream.pose;
    gst_structure_set(s, "head-pan-deg", G_TYPE_DOUBLE, pose.pan_deg, "head-tilt-deg", G_TYPE_DOUBLE, pose.tilt_deg,
                      "head-verge-left-deg", G_TYPE_DOUBLE, pose.verge_left_deg, "head-verge-right-deg", G_TYPE_DOUBLE,
                      pose.verge_right_deg, "head-zoom", G_TYPE_DOUBLE, pose.zoom, nullptr);
    gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

}  // namespace gc::gst
