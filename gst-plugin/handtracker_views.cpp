#include "handtracker_views.hpp"

#include "stereo/pointing_dwell.hpp"

#include <opencv2/imgproc.hpp>

namespace gc::gst {

bool PackedLayout::known() const
{
    return mode == GST_VIDEO_MULTIVIEW_MODE_SIDE_BY_SIDE || mode == GST_VIDEO_MULTIVIEW_MODE_TOP_BOTTOM;
}

cv::Size PackedLayout::view_size(cv::Size frame) const
{
    if (flags & GST_VIDEO_MULTIVIEW_FLAGS_HALF_ASPECT) return frame;
    return mode == GST_VIDEO_MULTIVIEW_MODE_TOP_BOTTOM ? cv::Size(frame.width, frame.height / 2)
                                                       : cv::Size(frame.width / 2, frame.height);
}

PackedLayout packed_layout(const GstVideoInfo& info, GstVideoMultiviewFramePacking mode_override,
                           GstVideoMultiviewFlags flags_override)
{
    if (mode_override != GST_VIDEO_MULTIVIEW_FRAME_PACKING_NONE)
        return {GstVideoMultiviewMode(mode_override), flags_override};
    return {GST_VIDEO_INFO_MULTIVIEW_MODE(&info), GST_VIDEO_INFO_MULTIVIEW_FLAGS(&info)};
}

void read_views(BgrReader readers[2], cv::Mat halves[2], const GstVideoFrame* packed, const PackedLayout& layout,
                const GstVideoFrame* left, const GstVideoFrame* right, SlotViews& out)
{
    if (packed) {
        if (!views_ready(packed)) return;
        const cv::Mat& whole = readers[0].read(*packed);
        const bool top_bottom = layout.mode == GST_VIDEO_MULTIVIEW_MODE_TOP_BOTTOM;
        const cv::Rect first =
            top_bottom ? cv::Rect(0, 0, whole.cols, whole.rows / 2) : cv::Rect(0, 0, whole.cols / 2, whole.rows);
        const cv::Rect second = top_bottom ? cv::Rect(0, whole.rows / 2, whole.cols, whole.rows / 2)
                                           : cv::Rect(whole.cols / 2, 0, whole.cols / 2, whole.rows);
        const bool right_first = (layout.flags & GST_VIDEO_MULTIVIEW_FLAGS_RIGHT_VIEW_FIRST) != 0;
        const cv::Size view = layout.view_size(whole.size());
        for (int i = 0; i < 2; ++i) {
            const cv::Mat part = whole((i == 0) != right_first ? first : second);
            if (part.size() == view)
                part.copyTo(halves[i]);
            else
                cv::resize(part, halves[i], view, 0, 0, cv::INTER_LINEAR);
            out.views[i] = halves[i];
            out.have[i] = true;
        }
        return;
    }
    const GstVideoFrame* frames[2] = {left, right};
    for (int i = 0; i < 2; ++i) {
        if (!views_ready(frames[i])) continue;
        const cv::Mat& bgr = readers[i].read(*frames[i]);
        // The tracker works on whole rows; padded strides are packed first.
        if (bgr.isContinuous())
            out.views[i] = bgr;
        else
            bgr.copyTo(halves[i]), out.views[i] = halves[i];
        out.have[i] = true;
    }
}

cv::Rect compose_view(const SlotViews& in, const ViewChoice& choice, const FrameResult& result,
                      std::span<const Particle> particles, cv::Size out_size, AttentionWindow& attention,
                      TrackingOverlay& overlay, cv::Mat& canvas, cv::Mat& scaled)
{
    if (!in.have[choice.shown]) {
        scaled.create(out_size, CV_8UC3);
        scaled.setTo(cv::Scalar::all(0));
        return cv::Rect(0, 0, out_size.width, out_size.height);
    }
    const cv::Mat& source = in.views[choice.shown];
    const EyeEstimate& eye = choice.shown == 1 ? result.right : result.left;
    cv::Mat base = source;
    if (choice.draw) {
        source.copyTo(canvas);
        overlay.draw(canvas, eye, particles, result.pointing.valid ? &result.pointing : nullptr);
        base = canvas;
    }
    cv::Rect view(0, 0, source.cols, source.rows);
    if (choice.attended)
        view = attention.update(source.size(), double(out_size.width) / out_size.height, result.left, choice.target);
    const cv::Mat cropped = base(view);
    if (cropped.size() == out_size)
        cropped.copyTo(scaled);
    else
        cv::resize(cropped, scaled, out_size, 0, 0, cropped.cols > out_size.width ? cv::INTER_AREA : cv::INTER_LINEAR);
    return view;
}

std::optional<cv::Rect2d> target_in_view(const std::optional<cv::Vec3d>& target, double region_mm,
                                         const StereoCalibration& calibration, const FrameResult& result)
{
    if (!target) return std::nullopt;
    const auto region = region_in_left_view(*target, region_mm, calibration, result.head.value_or(HeadPose{}));
    if (!region) return std::nullopt;
    const double w = region->width_px;
    return cv::Rect2d(region->centre.x - w / 2.0, region->centre.y - w / 2.0, w, w);
}

}  // namespace gc::gst
