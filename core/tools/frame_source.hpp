// One recorded input of gesturecam-track: a video file or a printf image-sequence pattern
// (e.g. left/%05d.png), read with cv::VideoCapture and delivered as 8-bit BGR frames.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace gc::tools {

// An input that cannot be opened or decoded; the message names the input and the cause.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Converts any frame VideoCapture may deliver (grey, BGR, BGRA; 8 or 16 bit) to CV_8UC3 BGR.
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
    case 1: cv::cvtColor(*src, out, cv::COLOR_GRAY2BGR); break;
    case 3: out = *src; break;
    case 4: cv::cvtColor(*src, out, cv::COLOR_BGRA2BGR); break;
    default:
        throw InputError("unsupported channel count " + std::to_string(src->channels()));
    }
}

class FrameSource {
public:
    // `role` names the input in messages ("left", "right").
    FrameSource(std::string path, std::string role) : path_(std::move(path)), role_(std::move(role))
    {
        sequence_ = path_.find('%') != std::string::npos;
        if (!sequence_) {
            std::error_code ec;
            if (!std::filesystem::exists(path_, ec))
                throw InputError(describe() + ": no such file");
            if (std::filesystem::is_directory(path_, ec))
                throw InputError(describe() + ": is a directory, expected a video file or an "
                                              "image-sequence pattern such as dir/%05d.png");
        }
        const int api = sequence_ ? cv::CAP_IMAGES : cv::CAP_ANY;
        if (!capture_.open(path_, api))
            throw InputError(describe() + (sequence_ ? ": no image matches the pattern (the "
                                                       "sequence must start at index 0 or 1)"
                                                     : ": cannot be opened as a video"));
        const double fps = capture_.get(cv::CAP_PROP_FPS);
        // Image sequences carry no time; video containers report their frame times.
        has_timestamps_ = !sequence_ && capture_.getBackendName() != "CV_IMAGES" && fps > 0.0;
    }

    // The next frame as CV_8UC3 BGR; false at the end of the input. Throws InputError when a
    // frame cannot be decoded into a supported format.
    bool read(cv::Mat& bgr)
    {
        if (!capture_.read(raw_) || raw_.empty())
            return false;
        try {
            to_bgr8(raw_, depth8_, bgr);
        } catch (const InputError& e) {
            throw InputError(describe() + " frame " + std::to_string(frames_read_) + ": " + e.what());
        }
        ++frames_read_;
        return true;
    }

    // Presentation time of the frame read last, from the container; -1 when unknown.
    std::int64_t timestamp_ns() const
    {
        if (!has_timestamps_)
            return -1;
        const double ms = capture_.get(cv::CAP_PROP_POS_MSEC);
        return ms >= 0.0 ? static_cast<std::int64_t>(ms * 1e6 + 0.5) : -1;
    }

    std::int64_t frames_read() const { return frames_read_; }
    const std::string& path() const { return path_; }
    std::string describe() const { return role_ + " input '" + path_ + "'"; }

private:
    std::string path_;
    std::string role_;
    bool sequence_ = false;
    bool has_timestamps_ = false;
    cv::VideoCapture capture_;
    cv::Mat raw_;
    cv::Mat depth8_;
    std::int64_t frames_read_ = 0;
};

}  // namespace gc::tools
