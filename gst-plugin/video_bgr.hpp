// Between mapped GstVideoFrames and the BGR cv::Mat the tracker works on, respecting the
// strides of every plane and without any videoconvert in the pipeline.
#pragma once

#include <gst/video/video.h>
#include <opencv2/core.hpp>

namespace gc::gst {

// The raw formats handtracker and handscenesrc accept (caps string list, no braces).
#define GC_INPUT_FORMATS "YUY2, NV12, I420, RGB, BGR, RGBx, BGRx, xRGB, xBGR, RGBA, BGRA"
#define GC_OUTPUT_FORMATS "BGR, RGB, BGRx, RGBx, xRGB, xBGR, BGRA, RGBA, I420, NV12"

// Reads frames as BGR. Keeps its scratch buffers between calls so that a stream of frames of
// one size allocates once.
class BgrReader {
public:
    // Returns the frame as CV_8UC3 BGR: a header over the frame's own memory for BGR input
    // (valid while the frame stays mapped), otherwise a converted copy owned by the reader.
    // Throws std::invalid_argument for an unsupported format or odd 4:2:0 sizes.
    const cv::Mat& read(const GstVideoFrame& frame);

private:
    cv::Mat bgr_;
    cv::Mat contiguous_;  // I420 planes packed the way cv::cvtColor wants them
    cv::Mat view_;
};

// Writes a CV_8UC3 BGR image of the frame's size into a mapped, writable frame of any of
// GC_OUTPUT_FORMATS. `scratch` is reused between calls. Throws std::invalid_argument on a
// size mismatch or an unsupported format.
void write_bgr(const cv::Mat& bgr, GstVideoFrame& frame, cv::Mat& scratch);

}  // namespace gc::gst
