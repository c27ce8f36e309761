#include "meta_estimate.hpp"

#include "meta_enums.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::gst {

TrackState track_state(GstHandPointingState s) { return value_in(kMetaStates, s).value_or(TrackState::Acquiring); }

Gesture track_gesture(GstHandPointingGesture g) { return value_in(kMetaGestures, g).value_or(Gesture::Unknown); }

EyeEstimate eye_from_meta(const GstHandPointingMeta& meta, bool right, cv::Size buffer_size)
{
    const bool stereo = (meta.flags & GST_HAND_POINTING_FLAG_STEREO) != 0;
    const GstHandPointingEye& in = right && stereo ? meta.right : meta.left;
    // The meta's 2D fields are in input pixels; the buffer shows view_* of that input.
    double sx = 1.0, sy = 1.0, ox = 0.0, oy = 0.0;
    if (meta.view_width > 0 && meta.view_height > 0) {
        sx = double(buffer_size.width) / meta.view_width;
        sy = double(buffer_size.height) / meta.view_height;
        ox = meta.view_x;
        oy = meta.view_y;
    }
    const auto map = [&](double x, double y) { return cv::Point2f(float((x - ox) * sx), float((y - oy) * sy)); };

    EyeEstimate eye;
    eye.state = track_state(in.state);
    eye.confidence = in.confidence;
    eye.palm = map(in.x, in.y);
    eye.mean.x = eye.palm.x;
    eye.mean.y = eye.palm.y;
    eye.fingertip = map(in.fingertip_x, in.fingertip_y);
    // An anisotropic scale turns image angles; the drawn ray follows the buffer's pixels.
    const double a = in.pointing_deg * std::numbers::pi / 180.0;
    eye.pointing_deg = std::atan2(std::sin(a) * sy, std::cos(a) * sx) * 180.0 / std::numbers::pi;
    eye.gesture = track_gesture(right && stereo ? meta.right_gesture : meta.left_gesture);
    const guint n = std::min<guint>(in.n_contour_points, GST_HAND_POINTING_MAX_CONTOUR_POINTS);
    eye.contour.reserve(n);
    for (guint i = 0; i < n; ++i) eye.contour.push_back(map(in.contour[i][0], in.contour[i][1]));
    const cv::Point2f box = map(in.bbox_x, in.bbox_y);
    eye.bbox = cv::Rect(int(box.x), int(box.y), int(in.bbox_width * sx), int(in.bbox_height * sy));
    return eye;
}

Pointing3D pointing_from_meta(const GstHandPointingMeta& meta)
{
    Pointing3D p;
    p.valid = (meta.flags & GST_HAND_POINTING_FLAG_HAS_3D) != 0;
    for (int i = 0; i < 3; ++i) {
        p.fingertip_mm[i] = meta.fingertip_mm[i];
        p.palm_mm[i] = meta.palm_mm[i];
        p.direction[i] = meta.direction[i];
    }
    p.azimuth_deg = meta.azimuth_deg;
    p.elevation_deg = meta.elevation_deg;
    return p;
}

}  // namespace gc::gst
