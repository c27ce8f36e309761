#include "handtracker_views.hpp"

#include <opencv2/imgproc.hpp>

namespace gc::gst {

void read_views(BgrReader readers[2], cv::Mat halves[2], const GstVideoFrame* packed, const GstVideoFrame* left,
                const GstVideoFrame* right, SlotViews& out)
{
    if (packed) {
        if (!views_ready(packed))
            return;
        const cv::Mat& whole = readers[0].read(*packed);
        const bool top_bottom = GST_VIDEO_INFO_MULTIVIEW_MODE(&packed->info) == GST_VIDEO_MULTIVIEW_MODE_TOP_BOTTOM;
        const cv::Rect first = top_bottom ? cv::Rect(0, 0, whole.cols, whole.rows / 2)
                                          : cv::Rect(0, 0, whole.cols / 2, whole.rows);
        const cv::Rect second = top_bottom ? cv::Rect(0, whole.rows / 2, whole.cols, whole.rows / 2)
                                           : cv::Rect(whole.cols / 2, 0, whole.cols / 2, whole.rows);
        whole(first).copyTo(halves[0]);
        whole(second).copyTo(halves[1]);
        out.views[0] = halves[0];
        out.views[1] = halves[1];
        out.have[0] = out.have[1] = true;
        return;
    }
    const GstVideoFrame* frames[2] = {left, right};
    for (int i = 0; i < 2; ++i) {
        if (!views_ready(frames[i]))
            continue;
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
        view = attention.update(source.size(), double(out_size.width) / out_size.height, result.left);
    const cv::Mat cropped = base(view);
    if (cropped.size() == out_size)
        cropped.copyTo(scaled);
    else
        cv::resize(cropped, scaled, out_size, 0, 0, cropped.cols > out_size.width ? cv::INTER_AREA : cv::INTER_LINEAR);
    return view;
}

}  // namespace gc::gst
