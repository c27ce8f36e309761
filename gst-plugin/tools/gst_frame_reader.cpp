#include "tools/gst_frame_reader.hpp"

#include "video_bgr.hpp"

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

namespace gc::tools {

namespace {

// videoconvert is a passthrough when the decoder already gives one of these, as in front of
// the element; otherwise it picks the same format the element's caps would make it pick.
constexpr const char* kRawCaps = "video/x-raw, format = (string) { " GC_INPUT_FORMATS " }";

// The first error on the bus, waiting up to `wait` for it (an element that fails the state
// change may post its error just after). "Internal data stream error." says little: then the
// debug text's last line, or "no video stream" when the stream found nothing to link to.
std::string pop_error(GstBus* bus, GstClockTime wait = 0)
{
    GstMessage* m = gst_bus_timed_pop_filtered(bus, wait, GST_MESSAGE_ERROR);
    if (!m) return "";
    GError* err = nullptr;
    gchar* debug = nullptr;
    gst_message_parse_error(m, &err, &debug);
    std::string text = err ? err->message : "unknown error";
    if (debug && err && g_error_matches(err, GST_STREAM_ERROR, GST_STREAM_ERROR_FAILED)) {
        const std::string d = debug;
        if (d.find("not-linked") != std::string::npos)
            text = "no video stream";  // decodebin found streams, none of them video
        else
            text.append(" ").append(d.substr(d.find_last_of('\n') + 1));
    }
    g_free(debug);
    g_clear_error(&err);
    gst_message_unref(m);
    return text;
}

bool is_video_decoder(GstElement* element)
{
    GstElementFactory* factory = gst_element_get_factory(element);
    if (!factory) return false;
    const std::string klass = gst_element_factory_get_metadata(factory, GST_ELEMENT_METADATA_KLASS);
    return klass.find("Decoder") != std::string::npos &&
           (klass.find("Video") != std::string::npos || klass.find("Image") != std::string::npos);
}

}  // namespace

struct GstFrameReader::Pipeline {
    GstElement* pipeline = nullptr;
    GstElement* sink = nullptr;
    GstBus* bus = nullptr;
    gc::gst::BgrReader bgr;
    cv::Size size;
    std::optional<std::int64_t> count;
    bool timed = false;  // the stream has a frame rate, so its buffers carry frame times

    // What the demuxer or parser handed the decoder: written on the streaming thread.
    std::mutex in_lock;
    std::multiset<GstClockTime> in_flight;  // times of frames that went in and did not come out yet
    std::int64_t inputs = 0;

    std::int64_t outputs = 0;
    std::int64_t dropped = 0;  // frames found undecodable so far
    std::int64_t pending_dropped = 0;
    cv::Mat held;  // the frame that follows the pending undecodable ones
    bool has_held = false;
    std::int64_t held_pts = -1;
    std::int64_t pts = -1;
    bool ended = false;

    ~Pipeline()
    {
        if (!pipeline) return;
        gst_element_set_state(pipeline, GST_STATE_NULL);
        if (bus) gst_object_unref(bus);
        if (sink) gst_object_unref(sink);
        gst_object_unref(pipeline);
    }

    static GstPadProbeReturn count_input(GstPad*, GstPadProbeInfo* info, gpointer self)
    {
        GstBuffer* buffer = GST_PAD_PROBE_INFO_BUFFER(info);
        if (GST_BUFFER_FLAG_IS_SET(buffer, GST_BUFFER_FLAG_HEADER)) return GST_PAD_PROBE_OK;
        auto* p = static_cast<Pipeline*>(self);
        const std::lock_guard<std::mutex> lock(p->in_lock);
        ++p->inputs;
        if (GST_BUFFER_PTS_IS_VALID(buffer)) p->in_flight.insert(GST_BUFFER_PTS(buffer));
        return GST_PAD_PROBE_OK;
    }

    // decodebin plugs the decoder while the pipeline starts: its input is counted from there.
    static void element_added(GstBin*, GstBin*, GstElement* element, gpointer self)
    {
        if (!is_video_decoder(element)) return;
        GstPad* pad = gst_element_get_static_pad(element, "sink");
        if (!pad) return;
        gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER, count_input, self, nullptr);
        gst_object_unref(pad);
    }

    void build(const std::string& path);
    void preroll();
    void read_caps();
    std::int64_t dropped_before(GstClockTime time);
    void take(GstSample* sample);
    void pull();
    void finish();
};

void GstFrameReader::Pipeline::build(const std::string& path)
{
    GError* err = nullptr;
    pipeline = gst_parse_launch("filesrc name=src ! decodebin ! videoconvert ! appsink name=sink", &err);
    if (!pipeline) {
        const std::string text = err ? err->message : "unknown error";
        g_clear_error(&err);
        throw std::runtime_error("cannot make a decoding pipeline: " + text);
    }
    g_clear_error(&err);  // a warning about a missing element would fail below
    GstElement* src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
    g_object_set(src, "location", path.c_str(), nullptr);
    gst_object_unref(src);
    sink = gst_bin_get_by_name(GST_BIN(pipeline), "sink");
    GstCaps* caps = gst_caps_from_string(kRawCaps);
    // Two frames queued at most: memory stays bounded whatever the length of the input.
    g_object_set(sink, "caps", caps, "sync", FALSE, "max-buffers", 2u, "drop", FALSE, "enable-last-sample", FALSE,
                 nullptr);
    gst_caps_unref(caps);
    bus = gst_element_get_bus(pipeline);
    g_signal_connect(pipeline, "deep-element-added", G_CALLBACK(element_added), this);
}

// Up to PAUSED: the first frame is decoded and the caps are fixed. Then PLAYING, so that the
// pull loop below drives the decoding.
void GstFrameReader::Pipeline::preroll()
{
    gst_element_set_state(pipeline, GST_STATE_PAUSED);
    if (gst_element_get_state(pipeline, nullptr, nullptr, GST_CLOCK_TIME_NONE) == GST_STATE_CHANGE_FAILURE) {
        const std::string why = pop_error(bus, GST_SECOND);
        throw std::runtime_error("cannot be decoded" + (why.empty() ? std::string() : " (" + why + ")"));
    }
    read_caps();
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
}

// The frame size and rate; the frame count from the video stream's duration (in frames when
// the demuxer can say so, else its time at the frame rate).
void GstFrameReader::Pipeline::read_caps()
{
    GstPad* pad = gst_element_get_static_pad(sink, "sink");
    GstCaps* caps = gst_pad_get_current_caps(pad);
    GstVideoInfo info;
    if (!caps || !gst_video_info_from_caps(&info, caps)) {
        if (caps) gst_caps_unref(caps);
        gst_object_unref(pad);
        throw std::runtime_error("cannot be decoded (no video stream)");
    }
    gst_caps_unref(caps);
    size = cv::Size(GST_VIDEO_INFO_WIDTH(&info), GST_VIDEO_INFO_HEIGHT(&info));
    timed = GST_VIDEO_INFO_FPS_N(&info) > 0;
    gint64 frames = 0, ns = 0;
    if (gst_pad_peer_query_duration(pad, GST_FORMAT_DEFAULT, &frames) && frames > 0)
        count = frames;
    else if (timed && gst_pad_peer_query_duration(pad, GST_FORMAT_TIME, &ns) && ns > 0)
        count = std::llround(double(ns) * GST_VIDEO_INFO_FPS_N(&info) / (1e9 * GST_VIDEO_INFO_FPS_D(&info)));
    gst_object_unref(pad);
}

// How many frames went into the decoder before the one shown at `time` and never came out:
// a decoder gives frames in presentation order, so those were dropped. A time that never went
// in (a decoder that makes its own times) says nothing.
std::int64_t GstFrameReader::Pipeline::dropped_before(GstClockTime time)
{
    const std::lock_guard<std::mutex> lock(in_lock);
    const auto at = in_flight.lower_bound(time);
    if (at == in_flight.end() || *at != time) return 0;
    const auto n = std::distance(in_flight.begin(), at);
    in_flight.erase(in_flight.begin(), std::next(at));
    return n;
}

void GstFrameReader::Pipeline::take(GstSample* sample)
{
    GstBuffer* buffer = gst_sample_get_buffer(sample);
    GstVideoInfo info;
    GstVideoFrame frame;
    if (!gst_video_info_from_caps(&info, gst_sample_get_caps(sample)) ||
        !gst_video_frame_map(&frame, &info, buffer, GST_MAP_READ))
        throw std::runtime_error("a decoded frame cannot be read");
    try {
        bgr.read(frame).copyTo(held);
    } catch (const std::invalid_argument& e) {
        gst_video_frame_unmap(&frame);
        throw std::runtime_error(e.what());
    }
    gst_video_frame_unmap(&frame);
    held_pts = timed && GST_BUFFER_PTS_IS_VALID(buffer) ? std::int64_t(GST_BUFFER_PTS(buffer)) : -1;
    has_held = true;
    ++outputs;
    if (GST_BUFFER_PTS_IS_VALID(buffer)) {
        const std::int64_t n = dropped_before(GST_BUFFER_PTS(buffer));
        pending_dropped += n;
        dropped += n;
    }
}

// Waits for the next decoded frame, the end of the stream or an error. An error ends the
// input like the end of the stream: the frames it cost are counted by finish().
void GstFrameReader::Pipeline::pull()
{
    while (true) {
        if (GstSample* sample = gst_app_sink_try_pull_sample(GST_APP_SINK(sink), 100 * GST_MSECOND)) {
            try {
                take(sample);
            } catch (...) {
                gst_sample_unref(sample);
                throw;
            }
            gst_sample_unref(sample);
            return;
        }
        if (gst_app_sink_is_eos(GST_APP_SINK(sink)) || !pop_error(bus).empty()) {
            finish();
            return;
        }
    }
}

// Frames that went into the decoder, or that the container counts, and never came out are
// undecodable: a stream cut short, a last frame the decoder refused.
void GstFrameReader::Pipeline::finish()
{
    ended = true;
    std::int64_t total = 0;
    {
        const std::lock_guard<std::mutex> lock(in_lock);
        total = std::max(inputs, count.value_or(0));
    }
    const std::int64_t missing = std::max<std::int64_t>(0, total - outputs - dropped);
    pending_dropped += missing;
    dropped += missing;
}

GstFrameReader::GstFrameReader(const std::string& path) : p_(std::make_unique<Pipeline>())
{
    gst_init(nullptr, nullptr);
    p_->build(path);
    p_->preroll();
}

GstFrameReader::~GstFrameReader() = default;

FrameStatus GstFrameReader::read(cv::Mat& bgr)
{
    while (true) {
        if (p_->pending_dropped > 0) {
            --p_->pending_dropped;
            return FrameStatus::Undecodable;
        }
        if (p_->has_held) {
            std::swap(bgr, p_->held);
            p_->pts = p_->held_pts;
            p_->has_held = false;
            return FrameStatus::Frame;
        }
        if (p_->ended) return FrameStatus::End;
        p_->pull();
    }
}

cv::Size GstFrameReader::frame_size() const { return p_->size; }

std::optional<std::int64_t> GstFrameReader::frame_count() const { return p_->count; }

std::int64_t GstFrameReader::timestamp_ns() const { return p_->pts; }

}  // namespace gc::tools
