// handtracker's pixels: the input views of one output slot read as BGR (two pads, or one
// side-by-side or top-bottom frame), and the output view composed from one of them.
#pragma once

#include "attention_window.hpp"
#include "tracking_overlay.hpp"
#include "video_bgr.hpp"

#include "tracker/pointing_tracker.hpp"

#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include <optional>
#include <span>

namespace gc::gst {

// A pad's prepared frame holds a buffer (a pad without data has none).
inline bool views_ready(const GstVideoFrame* frame) { return frame && frame->buffer; }

// The views of one output slot: [0] left, [1] right; `have[i]` when that view has a frame.
struct SlotViews {
    cv::Mat views[2];
    bool have[2] = {false, false};
};

// How both views share one frame on the `sink` pad (GStreamer's multiview description).
struct PackedLayout {
    GstVideoMultiviewMode mode = GST_VIDEO_MULTIVIEW_MODE_NONE;
    GstVideoMultiviewFlags flags = GST_VIDEO_MULTIVIEW_FLAGS_NONE;

    // Side by side or top and bottom: the packings the tracker can split.
    bool known() const;
    // One view's size in a frame of `frame` size, stretched back to full aspect when the
    // views were squeezed to half.
    cv::Size view_size(cv::Size frame) const;
};

// The layout of frames described by `info`: the override when one is set, else the caps'.
PackedLayout packed_layout(const GstVideoInfo& info, GstVideoMultiviewFramePacking mode_override,
                           GstVideoMultiviewFlags flags_override);

// Reads `packed` (both views in one frame, laid out as `layout` says) or `left` and `right`
// (either may be absent) into `out`, with `halves` as the storage for copies. Throws what
// the readers throw on a frame they cannot convert.
void read_views(BgrReader readers[2], cv::Mat halves[2], const GstVideoFrame* packed, const PackedLayout& layout,
                const GstVideoFrame* left, const GstVideoFrame* right, SlotViews& out);

// What the output shows and how it is drawn.
struct ViewChoice {
    int shown = 0;                     // the view shown: 0 left, 1 right
    bool attended = false;             // the left view cropped to the attention window
    bool draw = false;                 // the tracking drawn over it
    std::optional<cv::Rect2d> target;  // attended: the region a held pointing picked, framed instead of the hand
};

// Where the region `region_mm` wide around `target` (head frame) lies in the left view of
// `result`'s frame; nullopt without a target or when it is behind the camera.
std::optional<cv::Rect2d> target_in_view(const std::optional<cv::Vec3d>& target, double region_mm,
                                         const StereoCalibration& calibration, const FrameResult& result);

// Composes the output (at `out_size`) into `scaled`: the chosen view, drawn on in `canvas`
// when asked, cropped by `attention` when attended, scaled; black when the view is missing.
// `particles` are drawn with the estimate. Returns the shown rectangle in input pixels.
cv::Rect compose_view(const SlotViews& in, const ViewChoice& choice, const FrameResult& result,
                      std::span<const Particle> particles, cv::Size out_size, AttentionWindow& attention,
                      TrackingOverlay& overlay, cv::Mat& canvas, cv::Mat& scaled);

}  // namespace gc::gst
