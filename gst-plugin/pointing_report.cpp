#include "pointing_report.hpp"

#include "meta_enums.hpp"

#include <algorithm>
#include <numbers>

namespace gc::gst {
namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

void fill_eye(GstHandPointingEye& out, const EyeEstimate& eye, std::vector<float>& scratch)
{
    out.state = meta_state(eye.state);
    out.x = eye.mean.x;
    out.y = eye.mean.y;
    out.rotation_deg = degrees(eye.mean.rotation);
    out.scale = eye.mean.scale;
    out.confidence = eye.confidence;
    out.bbox_x = eye.bbox.x;
    out.bbox_y = eye.bbox.y;
    out.bbox_width = eye.bbox.width;
    out.bbox_height = eye.bbox.height;
    out.fingertip_x = eye.fingertip.x;
    out.fingertip_y = eye.fingertip.y;
    out.pointing_deg = eye.pointing_deg;
    scratch.clear();
    for (const cv::Point2f& p : eye.contour) {
        scratch.push_back(p.x);
        scratch.push_back(p.y);
    }
    gst_hand_pointing_eye_set_contour(&out, scratch.data(), guint(eye.contour.size()));
}

void set_structure(GstStructure* parent, const char* name, GstStructure* child)
{
    GValue value = G_VALUE_INIT;
    g_value_init(&value, GST_TYPE_STRUCTURE);
    g_value_take_boxed(&value, child);
    gst_structure_take_value(parent, name, &value);
}

GstStructure* eye_structure(const EyeEstimate& eye, bool with_contour)
{
    GstStructure* s = gst_structure_new(
        "hand-eye", "state", G_TYPE_STRING, to_string(eye.state).data(), "x", G_TYPE_DOUBLE, eye.mean.x, "y",
        G_TYPE_DOUBLE, eye.mean.y, "rotation-deg", G_TYPE_DOUBLE, degrees(eye.mean.rotation), "scale", G_TYPE_DOUBLE,
        eye.mean.scale, "confidence", G_TYPE_DOUBLE, eye.confidence, "bbox-x", G_TYPE_INT, eye.bbox.x, "bbox-y",
        G_TYPE_INT, eye.bbox.y, "bbox-width", G_TYPE_INT, eye.bbox.width, "bbox-height", G_TYPE_INT, eye.bbox.height,
        "fingertip-x", G_TYPE_DOUBLE, double(eye.fingertip.x), "fingertip-y", G_TYPE_DOUBLE, double(eye.fingertip.y),
        "pointing-deg", G_TYPE_DOUBLE, eye.pointing_deg, "gesture", G_TYPE_STRING, to_string(eye.gesture).data(),
        nullptr);
    if (with_contour) {
        // Flat (x0, y0, x1, y1, ...) keeps the serialised message readable and cheap.
        GValue array = G_VALUE_INIT;
        gst_value_array_init(&array, guint(2 * eye.contour.size()));
        for (const cv::Point2f& p : eye.contour) {
            for (float c : {p.x, p.y}) {
                GValue item = G_VALUE_INIT;
                g_value_init(&item, G_TYPE_FLOAT);
                g_value_set_float(&item, c);
                gst_value_array_append_and_take_value(&array, &item);
            }
        }
        gst_structure_take_value(s, "contour", &array);
    }
    return s;
}

}  // namespace

void set_vec3(GstStructure* s, const char* name, const cv::Vec3d& v)
{
    GValue array = G_VALUE_INIT;
    gst_value_array_init(&array, 3);
    for (int i = 0; i < 3; ++i) {
        GValue item = G_VALUE_INIT;
        g_value_init(&item, G_TYPE_DOUBLE);
        g_value_set_double(&item, v[i]);
        gst_value_array_append_and_take_value(&array, &item);
    }
    gst_structure_take_value(s, name, &array);
}

GstHandPointingGesture meta_gesture(Gesture g) { return name_in(kMetaGestures, g, GST_HAND_POINTING_GESTURE_UNKNOWN); }

GstHandPointingState meta_state(TrackState s) { return name_in(kMetaStates, s, GST_HAND_POINTING_STATE_ACQUIRING); }

void fill_meta(GstHandPointingMeta& meta, const FrameResult& result, const ReportContext& context,
               std::vector<float>& scratch)
{
    meta.frame = guint64(std::max<std::int64_t>(result.frame, 0));
    meta.state = meta_state(result.state);
    guint flags = GST_HAND_POINTING_FLAG_NONE;
    if (result.stereo) flags |= GST_HAND_POINTING_FLAG_STEREO;
    if (result.pointing.valid) flags |= GST_HAND_POINTING_FLAG_HAS_3D;
    if (result.head) flags |= GST_HAND_POINTING_FLAG_HAS_HEAD;
    if (context.incomplete) flags |= GST_HAND_POINTING_FLAG_INCOMPLETE;
    if (context.full_view) flags |= GST_HAND_POINTING_FLAG_FULL_VIEW;
    meta.flags = flags;
    fill_eye(meta.left, result.left, scratch);
    fill_eye(meta.right, result.stereo ? result.right : EyeEstimate{}, scratch);
    const Pointing3D& p = result.pointing;
    for (int i = 0; i < 3; ++i) {
        meta.fingertip_mm[i] = p.valid ? p.fingertip_mm[i] : 0.0;
        meta.palm_mm[i] = p.valid ? p.palm_mm[i] : 0.0;
        meta.direction[i] = p.valid ? p.direction[i] : 0.0;
    }
    meta.azimuth_deg = p.valid ? p.azimuth_deg : 0.0;
    meta.elevation_deg = p.valid ? p.elevation_deg : 0.0;
    const HeadPose head = result.head.value_or(HeadPose{});
    meta.head_pan_deg = head.pan_deg;
    meta.head_tilt_deg = head.tilt_deg;
    meta.head_verge_left_deg = head.verge_left_deg;
    meta.head_verge_right_deg = head.verge_right_deg;
    meta.view_x = context.view.x;
    meta.view_y = context.view.y;
    meta.view_width = context.view.width;
    meta.view_height = context.view.height;
    meta.left_gesture = meta_gesture(result.left.gesture);
    meta.right_gesture = result.stereo ? meta_gesture(result.right.gesture) : GST_HAND_POINTING_GESTURE_UNKNOWN;
}

GstStructure* pointing_structure(const FrameResult& result, const ReportContext& context, bool with_contours)
{
    GstStructure* s =
        gst_structure_new("hand-pointing", "frame", G_TYPE_UINT64, guint64(std::max<std::int64_t>(result.frame, 0)),
                          "state", G_TYPE_STRING, to_string(result.state).data(), "stereo", G_TYPE_BOOLEAN,
                          gboolean(result.stereo), "incomplete", G_TYPE_BOOLEAN, gboolean(context.incomplete), nullptr);
    set_structure(s, "left", eye_structure(result.left, with_contours));
    if (result.stereo) set_structure(s, "right", eye_structure(result.right, with_contours));
    if (result.pointing.valid) {
        const Pointing3D& p = result.pointing;
        GstStructure* ps = gst_structure_new("hand-pointing-3d", "azimuth-deg", G_TYPE_DOUBLE, p.azimuth_deg,
                                             "elevation-deg", G_TYPE_DOUBLE, p.elevation_deg, nullptr);
        set_vec3(ps, "fingertip-mm", p.fingertip_mm);
        set_vec3(ps, "palm-mm", p.palm_mm);
        set_vec3(ps, "direction", p.direction);
        set_structure(s, "pointing", ps);
    }
    if (result.head) {
        const HeadPose& h = *result.head;
        set_structure(s, "head",
                      gst_structure_new("head-pose", "pan-deg", G_TYPE_DOUBLE, h.pan_deg, "tilt-deg", G_TYPE_DOUBLE,
                                        h.tilt_deg, "verge-left-deg", G_TYPE_DOUBLE, h.verge_left_deg,
                                        "verge-right-deg", G_TYPE_DOUBLE, h.verge_right_deg, "zoom", G_TYPE_DOUBLE,
                                        h.zoom, nullptr));
    }
    return s;
}

}  // namespace gc::gst
