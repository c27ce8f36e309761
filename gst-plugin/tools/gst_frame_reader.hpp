// One file (a video in any container GStreamer decodes, or one image) decoded by GStreamer
// the way the handtracker element receives it from pipelines/files.sh: decodebin, then
// videoconvert to a format the element accepts, then the element's own BGR conversion
// (video_bgr: GStreamer's converter, honouring the caps' colorimetry and range). The tools
// read through it so that they see the same frames as the element.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace gc::tools {

enum class FrameStatus {
    Frame,        // a frame was read
    End,          // the input has no more frames
    Undecodable,  // the input holds this frame but it cannot be decoded; the reader moved past it
};

class GstFrameReader {
public:
    // Opens `path` and decodes its first frame (so the frame size is known). Throws
    // std::runtime_error with GStreamer's reason when nothing of it can be decoded.
    explicit GstFrameReader(const std::string& path);
    ~GstFrameReader();
    GstFrameReader(const GstFrameReader&) = delete;
    GstFrameReader& operator=(const GstFrameReader&) = delete;

    // The next frame as CV_8UC3 BGR. A frame the demuxer handed to the decoder that never came
    // out of it (a decoder may drop a broken frame with only a warning) is Undecodable, in its
    // place in the stream; so are frames the container counts beyond a stream cut short.
    FrameStatus read(cv::Mat& bgr);

    cv::Size frame_size() const;
    // The container's frame count (its duration at its frame rate); nullopt when unknown.
    std::optional<std::int64_t> frame_count() const;
    // Presentation time of the frame read last, in ns; -1 for an input without frame times
    // (an image).
    std::int64_t timestamp_ns() const;

private:
    struct Pipeline;
    std::unique_ptr<Pipeline> p_;
};

}  // namespace gc::tools
