// One recorded input of gesturecam-track: a video file (read with cv::VideoCapture) or a
// printf image-sequence pattern (e.g. left/%05d.png, each file read with cv::imread),
// delivered as 8-bit BGR frames. A frame that exists but cannot be decoded is reported as
// such, not taken for the end of the input.
#pragma once

#include "tools/image_file.hpp"
#include "tools/image_sequence.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace gc::tools {

// Converts any frame the readers may deliver (grey, BGR, BGRA; 8 or 16 bit) to CV_8UC3 BGR.
// `out` may alias `in` when no conversion is needed.
inline void to_bgr8(const cv::Mat& in, cv::Mat& depth8, cv::Mat& out)
{
    const cv::Mat* src = &in;
    if (in.depth() != CV_8U) {
        // 16-bit spans 0..65535, floating point 0..1 (OpenCV's conventions).
        if (in.depth() == CV_16U)
            in.convertTo(depth8, CV_8U, 1.0 / 257.0);
        else if (in.depth() == CV_32F || in.depth() == CV_64F)
            in.convertTo(depth8, CV_8U, 255.0);
        else
            throw InputError("unsupported pixel type " + cv::typeToString(in.type()));
        src = &depth8;
    }
    switch (src->channels()) {
    case 1:
        cv::cvtColor(*src, out, cv::COLOR_GRAY2BGR);
        break;
    case 3:
        out = *src;
        break;
    case 4:
        cv::cvtColor(*src, out, cv::COLOR_BGRA2BGR);
        break;
    default:
        throw InputError("unsupported channel count " + std::to_string(src->channels()));
    }
}

enum class FrameStatus {
    Frame,        // a frame was read
    End,          // the input has no more frames
    Undecodable,  // the input holds this frame but it cannot be decoded; the source moved past it
};

class FrameSource {
public:
    // `role` names the input in messages ("left", "right").
    FrameSource(std::string path, std::string role) : path_(std::move(path)), role_(std::move(role))
    {
        if (path_.find('%') != std::string::npos) {
            sequence_.emplace(path_, describe());
            return;
        }
        std::error_code ec;
        if (!std::filesystem::exists(path_, ec)) throw InputError(describe() + ": no such file");
        if (std::filesystem::is_directory(path_, ec))
            throw InputError(describe() + ": is a directory, expected a video file or an "
                                          "image-sequence pattern such as dir/%05d.png");
        // A single image given as the input: its declared size is checked before decoding (not
        // in a FIFO, whose bytes the reading would take from the decoder).
        if (std::filesystem::is_regular_file(path_, ec))
            if (const std::optional<cv::Size> declared = image_file_size(path_))
                check_frame_size(*declared, describe());
        if (!capture_.open(path_, cv::CAP_ANY)) throw InputError(describe() + ": cannot be opened as a video");
        check_frame_size(cv::Size(static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_WIDTH)),
                                  static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_HEIGHT))),
                         describe());
        const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
        if (count > 0.0) frame_count_ = static_cast<std::int64_t>(count);
        // Video containers report their frame times; the image reader behind a single file does not.
        has_timestamps_ = capture_.getBackendName() != "CV_IMAGES" && capture_.get(cv::CAP_PROP_FPS) > 0.0;
    }

    // Reads frame next_index() as CV_8UC3 BGR. Throws InputError for a frame larger than
    // kMaxFrameSide a side or of a pixel format that cannot be converted.
    FrameStatus read(cv::Mat& bgr)
    {
        const FrameStatus status = sequence_ ? read_file(raw_) : read_video(raw_);
        if (status != FrameStatus::Frame) return status;
        try {
            check_frame_size(raw_.size(), "frame " + std::to_string(next_index_));
            to_bgr8(raw_, depth8_, bgr);
        } catch (const InputError& e) {
            throw InputError(describe() + ": " + e.what());
        }
        ++next_index_;
        return status;
    }

    // The index of the frame the next read() gives, from 0.
    std::int64_t next_index() const { return next_index_; }

    // "frame N of M ('file')" for messages: the index, the count when the input knows it, and
    // the file of an image sequence.
    std::string frame_text(std::int64_t index) const
    {
        std::string text = "frame " + std::to_string(index);
        if (const std::optional<std::int64_t> count = frame_count()) text += " of " + std::to_string(*count);
        if (sequence_) text += " ('" + sequence_->path(index) + "')";
        return text;
    }

    // How many frames the input holds: the files of a sequence, the container's frame count.
    std::optional<std::int64_t> frame_count() const
    {
        return sequence_ ? std::optional<std::int64_t>(sequence_->length()) : frame_count_;
    }

    // Presentation time of the frame read last, from the container; -1 when unknown.
    std::int64_t timestamp_ns() const
    {
        if (!has_timestamps_) return -1;
        const double ms = capture_.get(cv::CAP_PROP_POS_MSEC);
        return ms >= 0.0 ? static_cast<std::int64_t>(ms * 1e6 + 0.5) : -1;
    }

    std::string describe() const { return role_ + " input '" + path_ + "'"; }

private:
    FrameStatus read_file(cv::Mat& raw)
    {
        if (next_index_ >= sequence_->length()) return FrameStatus::End;
        raw = read_image_file(sequence_->path(next_index_), cv::IMREAD_UNCHANGED,
                              describe() + " " + frame_text(next_index_));
        return raw.empty() ? skip() : FrameStatus::Frame;
    }

    // The container's frame count tells a frame that fails to decode from the end of the
    // stream (cv::VideoCapture::read() answers false for both).
    FrameStatus read_video(cv::Mat& raw)
    {
        if (capture_.read(raw) && !raw.empty()) return FrameStatus::Frame;
        return frame_count_ && next_index_ < *frame_count_ ? skip() : FrameStatus::End;
    }

    FrameStatus skip()
    {
        ++next_index_;
        return FrameStatus::Undecodable;
    }

    std::string path_;
    std::string role_;
    std::optional<ImageSequence> sequence_;
    cv::VideoCapture capture_;
    std::optional<std::int64_t> frame_count_;
    bool has_timestamps_ = false;
    cv::Mat raw_;
    cv::Mat depth8_;
    std::int64_t next_index_ = 0;
};

}  // namespace gc::tools
