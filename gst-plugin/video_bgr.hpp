// Between mapped GstVideoFrames and the BGR cv::Mat the tracker works on. GStreamer's own
// converter does the work, so the caps' colorimetry (BT.601, BT.709, ...) and range (limited
// or full) are honoured exactly as videoconvert would, without a videoconvert in the pipeline.
#pragma once

#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include <memory>

namespace gc::gst {

// The raw formats handtracker accepts, and those handscenesrc produces (caps string lists,
// no braces).
#define GC_INPUT_FORMATS "YUY2, NV12, I420, RGB, BGR, RGBx, BGRx, xRGB, xBGR, RGBA, BGRA"
#define GC_OUTPUT_FORMATS "BGR, RGB, BGRx, RGBx, xRGB, xBGR, BGRA, RGBA, I420, NV12"

// One GstVideoConverter, made again only when the formats on either side change.
class CachedConverter {
public:
    // Converts `src` into `dst`. Throws std::invalid_argument when GStreamer cannot convert
    // between the two (e.g. an odd width in a 4:2:0 format).
    void convert(const GstVideoFrame& src, GstVideoFrame& dst);

private:
    struct Free {
        void operator()(GstVideoConverter* c) const { gst_video_converter_free(c); }
    };
    std::unique_ptr<GstVideoConverter, Free> converter_;
    GstVideoInfo in_{};
    GstVideoInfo out_{};
};

// Reads frames as BGR. Keeps its buffers between calls so that a stream of frames of one
// size allocates once.
class BgrReader {
public:
    // Returns the frame as CV_8UC3 BGR without row padding: a header over the frame's own
    // memory for unpadded BGR input (valid while the frame stays mapped), otherwise a
    // converted copy owned by the reader. Throws std::invalid_argument for an unsupported
    // format or size.
    const cv::Mat& read(const GstVideoFrame& frame);

private:
    cv::Mat bgr_;
    cv::Mat view_;
    CachedConverter converter_;
};

// Writes CV_8UC3 BGR images into mapped, writable frames of any of GC_OUTPUT_FORMATS, in
// the colorimetry their caps say.
class BgrWriter {
public:
    // Throws std::invalid_argument on a size mismatch or an unsupported format.
    void write(const cv::Mat& bgr, GstVideoFrame& frame);

private:
    CachedConverter converter_;
};

}  // namespace gc::gst
