#include "video_bgr.hpp"

#include <opencv2/imgproc.hpp>

#include <stdexcept>
#include <string>

namespace gc::gst {
namespace {

std::string format_name(const GstVideoFrame& frame)
{
    return gst_video_format_to_string(GST_VIDEO_FRAME_FORMAT(&frame));
}

void require_even(const GstVideoFrame& frame)
{
    const int w = GST_VIDEO_FRAME_WIDTH(&frame);
    const int h = GST_VIDEO_FRAME_HEIGHT(&frame);
    if (w % 2 != 0 || h % 2 != 0)
        throw std::invalid_argument(format_name(frame) + " frames must have an even width and height, got " +
                                    std::to_string(w) + "x" + std::to_string(h));
}

// Channel pairs for cv::mixChannels between 4-byte formats with padding first and BGR.
constexpr int kXrgbToBgr[] = {3, 0, 2, 1, 1, 2};
constexpr int kXbgrToBgr[] = {1, 0, 2, 1, 3, 2};
constexpr int kBgrToXrgb[] = {2, 1, 1, 2, 0, 3};
constexpr int kBgrToXbgr[] = {0, 1, 1, 2, 2, 3};

}  // namespace

const cv::Mat& BgrReader::read(const GstVideoFrame& frame)
{
    const GstVideoFormat format = GST_VIDEO_FRAME_FORMAT(&frame);
    const int w = GST_VIDEO_FRAME_WIDTH(&frame);
    const int h = GST_VIDEO_FRAME_HEIGHT(&frame);
    auto packed = [&](int channels) {
        return cv::Mat(h, w, CV_8UC(channels), GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                       static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
    };
    switch (format) {
    case GST_VIDEO_FORMAT_BGR:
        view_ = packed(3);
        return view_;
    case GST_VIDEO_FORMAT_RGB:
        cv::cvtColor(packed(3), bgr_, cv::COLOR_RGB2BGR);
        return bgr_;
    case GST_VIDEO_FORMAT_BGRx:
    case GST_VIDEO_FORMAT_BGRA:
        cv::cvtColor(packed(4), bgr_, cv::COLOR_BGRA2BGR);
        return bgr_;
    case GST_VIDEO_FORMAT_RGBx:
    case GST_VIDEO_FORMAT_RGBA:
        cv::cvtColor(packed(4), bgr_, cv::COLOR_RGBA2BGR);
        return bgr_;
    case GST_VIDEO_FORMAT_xRGB:
    case GST_VIDEO_FORMAT_xBGR: {
        bgr_.create(h, w, CV_8UC3);
        const cv::Mat src = packed(4);
        cv::mixChannels(&src, 1, &bgr_, 1, format == GST_VIDEO_FORMAT_xRGB ? kXrgbToBgr : kXbgrToBgr, 3);
        return bgr_;
    }
    case GST_VIDEO_FORMAT_YUY2:
        cv::cvtColor(packed(2), bgr_, cv::COLOR_YUV2BGR_YUY2);
        return bgr_;
    case GST_VIDEO_FORMAT_NV12: {
        require_even(frame);
        const cv::Mat y(h, w, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                        static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
        const cv::Mat uv(h / 2, w / 2, CV_8UC2, GST_VIDEO_FRAME_PLANE_DATA(&frame, 1),
                         static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 1)));
        cv::cvtColorTwoPlane(y, uv, bgr_, cv::COLOR_YUV2BGR_NV12);
        return bgr_;
    }
    case GST_VIDEO_FORMAT_I420: {
        // cvtColor wants the three planes back to back without row padding.
        require_even(frame);
        contiguous_.create(h + h / 2, w, CV_8UC1);
        const cv::Mat y(h, w, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                        static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
        y.copyTo(contiguous_.rowRange(0, h));
        for (int p = 1; p <= 2; ++p) {
            const cv::Mat chroma(h / 2, w / 2, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, p),
                                 static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, p)));
            uchar* dst = contiguous_.ptr(h) + static_cast<size_t>(p - 1) * (w / 2) * (h / 2);
            chroma.copyTo(cv::Mat(h / 2, w / 2, CV_8UC1, dst));
        }
        cv::cvtColor(contiguous_, bgr_, cv::COLOR_YUV2BGR_I420);
        return bgr_;
    }
    default:
        throw std::invalid_argument("unsupported input format " + format_name(frame));
    }
}

void write_bgr(const cv::Mat& bgr, GstVideoFrame& frame, cv::Mat& scratch)
{
    const GstVideoFormat format = GST_VIDEO_FRAME_FORMAT(&frame);
    const int w = GST_VIDEO_FRAME_WIDTH(&frame);
    const int h = GST_VIDEO_FRAME_HEIGHT(&frame);
    if (bgr.type() != CV_8UC3 || bgr.cols != w || bgr.rows != h)
        throw std::invalid_argument("write_bgr: a " + std::to_string(bgr.cols) + "x" +
                                    std::to_string(bgr.rows) + " " + cv::typeToString(bgr.type()) +
                                    " image does not fit a " + std::to_string(w) + "x" +
                                    std::to_string(h) + " " + format_name(frame) + " frame");
    auto packed = [&](int channels) {
        return cv::Mat(h, w, CV_8UC(channels), GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                       static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
    };
    switch (format) {
    case GST_VIDEO_FORMAT_BGR: {
        cv::Mat dst = packed(3);
        bgr.copyTo(dst);
        return;
    }
    case GST_VIDEO_FORMAT_RGB: {
        cv::Mat dst = packed(3);
        cv::cvtColor(bgr, dst, cv::COLOR_BGR2RGB);
        return;
    }
    case GST_VIDEO_FORMAT_BGRx:
    case GST_VIDEO_FORMAT_BGRA: {
        cv::Mat dst = packed(4);
        cv::cvtColor(bgr, dst, cv::COLOR_BGR2BGRA);
        return;
    }
    case GST_VIDEO_FORMAT_RGBx:
    case GST_VIDEO_FORMAT_RGBA: {
        cv::Mat dst = packed(4);
        cv::cvtColor(bgr, dst, cv::COLOR_BGR2RGBA);
        return;
    }
    case GST_VIDEO_FORMAT_xRGB:
    case GST_VIDEO_FORMAT_xBGR: {
        cv::Mat dst = packed(4);
        dst.setTo(cv::Scalar::all(255));
        cv::mixChannels(&bgr, 1, &dst, 1, format == GST_VIDEO_FORMAT_xRGB ? kBgrToXrgb : kBgrToXbgr, 3);
        return;
    }
    case GST_VIDEO_FORMAT_I420:
    case GST_VIDEO_FORMAT_NV12: {
        require_even(frame);
        cv::cvtColor(bgr, scratch, cv::COLOR_BGR2YUV_I420);  // (h * 3 / 2) x w, planes back to back
        scratch.rowRange(0, h).copyTo(cv::Mat(h, w, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                                              static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0))));
        const cv::Mat u(h / 2, w / 2, CV_8UC1, scratch.ptr(h));
        const cv::Mat v(h / 2, w / 2, CV_8UC1, scratch.ptr(h) + static_cast<size_t>(w / 2) * (h / 2));
        if (format == GST_VIDEO_FORMAT_I420) {
            u.copyTo(cv::Mat(h / 2, w / 2, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, 1),
                             static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 1))));
            v.copyTo(cv::Mat(h / 2, w / 2, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(&frame, 2),
                             static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 2))));
        } else {
            cv::Mat uv(h / 2, w / 2, CV_8UC2, GST_VIDEO_FRAME_PLANE_DATA(&frame, 1),
                       static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 1)));
            const cv::Mat planes[] = {u, v};
            cv::merge(planes, 2, uv);
        }
        return;
    }
    default:
        throw std::invalid_argument("unsupported output format " + format_name(frame));
    }
}

}  // namespace gc::gst
