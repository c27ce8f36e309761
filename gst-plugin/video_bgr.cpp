#include "video_bgr.hpp"

#include <stdexcept>
#include <string>

namespace gc::gst {
namespace {

std::string describe(const GstVideoInfo& info)
{
    return std::to_string(GST_VIDEO_INFO_WIDTH(&info)) + "x" + std::to_string(GST_VIDEO_INFO_HEIGHT(&info)) + " " +
           gst_video_format_to_string(GST_VIDEO_INFO_FORMAT(&info));
}

bool supported(GstVideoFormat format, const char* list)
{
    const std::string formats = std::string(", ") + list + ",";
    return formats.find(std::string(" ") + gst_video_format_to_string(format) + ",") != std::string::npos;
}

// A GstVideoFrame over a BGR cv::Mat, filled by hand rather than mapped from a GstBuffer so
// that no buffer is allocated per frame; the converter reads only the info and plane data.
// The frame rate, aspect and layout are the other side's: the converter changes only pixels.
GstVideoFrame bgr_frame(const cv::Mat& bgr, const GstVideoInfo& other_side)
{
    GstVideoFrame frame{};
    gst_video_info_set_interlaced_format(&frame.info, GST_VIDEO_FORMAT_BGR, GST_VIDEO_INFO_INTERLACE_MODE(&other_side),
                                         guint(bgr.cols), guint(bgr.rows));
    frame.info.fps_n = other_side.fps_n;
    frame.info.fps_d = other_side.fps_d;
    frame.info.par_n = other_side.par_n;
    frame.info.par_d = other_side.par_d;
    frame.info.stride[0] = int(bgr.step[0]);
    frame.info.size = bgr.step[0] * size_t(bgr.rows);
    frame.data[0] = bgr.data;
    return frame;
}

bool same_conversion(const GstVideoInfo& a, const GstVideoInfo& b)
{
    return GST_VIDEO_INFO_FORMAT(&a) == GST_VIDEO_INFO_FORMAT(&b) && a.width == b.width && a.height == b.height &&
           gst_video_colorimetry_is_equal(&a.colorimetry, &b.colorimetry) &&
           GST_VIDEO_INFO_CHROMA_SITE(&a) == GST_VIDEO_INFO_CHROMA_SITE(&b) &&
           GST_VIDEO_INFO_INTERLACE_MODE(&a) == GST_VIDEO_INFO_INTERLACE_MODE(&b);
}

}  // namespace

void CachedConverter::convert(const GstVideoFrame& src, GstVideoFrame& dst)
{
    if (!converter_ || !same_conversion(src.info, in_) || !same_conversion(dst.info, out_)) {
        converter_.reset();
        in_ = src.info;
        out_ = dst.info;
        // One thread: the tracker already works on both eyes at once.
        GstStructure* config =
            gst_structure_new("GstVideoConverter", GST_VIDEO_CONVERTER_OPT_THREADS, G_TYPE_UINT, 1u, nullptr);
        converter_.reset(gst_video_converter_new(&in_, &out_, config));
        if (!converter_)
            throw std::invalid_argument("GStreamer cannot convert " + describe(in_) + " to " + describe(out_));
    }
    gst_video_converter_frame(converter_.get(), &src, &dst);
}

const cv::Mat& BgrReader::read(const GstVideoFrame& frame)
{
    const GstVideoInfo& info = frame.info;
    if (!supported(GST_VIDEO_INFO_FORMAT(&info), GC_INPUT_FORMATS))
        throw std::invalid_argument("unsupported input format " + describe(info));
    const int w = GST_VIDEO_INFO_WIDTH(&info);
    const int h = GST_VIDEO_INFO_HEIGHT(&info);
    if (GST_VIDEO_INFO_FORMAT(&info) == GST_VIDEO_FORMAT_BGR && GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0) == 3 * w) {
        view_ = cv::Mat(h, w, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0));
        return view_;
    }
    bgr_.create(h, w, CV_8UC3);
    GstVideoFrame dst = bgr_frame(bgr_, info);
    converter_.convert(frame, dst);
    return bgr_;
}

void BgrWriter::write(const cv::Mat& bgr, GstVideoFrame& frame)
{
    const GstVideoInfo& info = frame.info;
    if (bgr.type() != CV_8UC3 || bgr.cols != GST_VIDEO_INFO_WIDTH(&info) || bgr.rows != GST_VIDEO_INFO_HEIGHT(&info))
        throw std::invalid_argument("a " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) + " " +
                                    cv::typeToString(bgr.type()) + " image does not fit a " + describe(info) +
                                    " frame");
    if (!supported(GST_VIDEO_INFO_FORMAT(&info), GC_OUTPUT_FORMATS))
        throw std::invalid_argument("unsupported output format " + describe(info));
    if (GST_VIDEO_INFO_FORMAT(&info) == GST_VIDEO_FORMAT_BGR) {
        cv::Mat dst(bgr.rows, bgr.cols, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                    size_t(GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
        bgr.copyTo(dst);
        return;
    }
    const GstVideoFrame src = bgr_frame(bgr, info);
    converter_.convert(src, frame);
}

}  // namespace gc::gst
