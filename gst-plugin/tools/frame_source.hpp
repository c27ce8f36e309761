// One recorded input of gesturecam-track: a video file, one image, or a printf
// image-sequence pattern (e.g. left/%05d.png), decoded by GStreamer as the handtracker
// element receives it (gst_frame_reader.hpp) and delivered as 8-bit BGR frames. A frame that
// exists but cannot be decoded is reported as such, not taken for the end of the input.
#pragma once

#include "tools/gst_frame_reader.hpp"
#include "tools/image_file.hpp"
#include "tools/image_sequence.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace gc::tools {

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
        try {
            video_ = std::make_unique<GstFrameReader>(path_);
        } catch (const std::runtime_error& e) {
            throw InputError(describe() + ": " + e.what());
        }
        check_frame_size(video_->frame_size(), describe());
    }

    // Reads frame next_index() as CV_8UC3 BGR. Throws InputError for a frame larger than
    // kMaxFrameSide a side or of a pixel format that cannot be converted.
    FrameStatus read(cv::Mat& bgr)
    {
        FrameStatus status = FrameStatus::End;
        try {
            status = sequence_ ? read_file(bgr) : video_->read(bgr);
        } catch (const InputError&) {
            throw;
        } catch (const std::runtime_error& e) {  // a decoded frame GStreamer cannot convert
            throw InputError(describe() + ": " + e.what());
        }
        if (status == FrameStatus::Frame)
            check_frame_size(bgr.size(), describe() + ": frame " + std::to_string(next_index_));
        if (status != FrameStatus::End) ++next_index_;
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
        return sequence_ ? std::optional<std::int64_t>(sequence_->length()) : video_->frame_count();
    }

    // Presentation time of the frame read last, from the container; -1 when unknown.
    std::int64_t timestamp_ns() const { return video_ ? video_->timestamp_ns() : -1; }

    std::string describe() const { return role_ + " input '" + path_ + "'"; }

private:
    // Each file of a sequence is decoded on its own, so that a file that does not decode is
    // known for certain (a decoder fed the whole sequence may drop it with only a warning).
    // Its declared size is checked first, before anything is decoded.
    FrameStatus read_file(cv::Mat& bgr)
    {
        if (next_index_ >= sequence_->length()) return FrameStatus::End;
        const std::string file = sequence_->path(next_index_);
        std::error_code ec;
        const std::string what = describe() + " " + frame_text(next_index_);
        if (!std::filesystem::is_regular_file(file, ec))
            throw InputError(what + ": '" + file + "' is not a regular file");
        if (const std::optional<cv::Size> declared = image_file_size(file)) check_frame_size(*declared, what);
        try {
            GstFrameReader image(file);
            return image.read(bgr) == FrameStatus::Frame ? FrameStatus::Frame : FrameStatus::Undecodable;
        } catch (const std::runtime_error&) {
            return FrameStatus::Undecodable;
        }
    }

    std::string path_;
    std::string role_;
    std::optional<ImageSequence> sequence_;
    std::unique_ptr<GstFrameReader> video_;
    std::int64_t next_index_ = 0;
};

}  // namespace gc::tools
