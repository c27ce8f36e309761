// The element-level head-jump run, shared by its test (a few jumps) and its benchmark
// (10 000 frames): two handscenesrc eyes on a fixed rig whose pose a GstController makes
// jump (head-pan, head-tilt), into handtracker with steer off and a json-location file.
// The scene's hand-truth messages say when the hand is in view; the JSON lines say when
// the tracker has it again.
#pragma once

#include <gst/controller/gstdirectcontrolbinding.h>
#include <gst/controller/gstinterpolationcontrolsource.h>
#include <gst/gst.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <random>
#include <string>
#include <vector>

namespace gc::chaos {

constexpr int kFps = 30;
constexpr int kJudgedVisibleFrames = 60;  // a jump is judged if the hand stays in view this long
constexpr int kFoundWithin = 30;          // and must be tracked again within this many frames

struct RigJump {
    int frame = 0;  // the first frame rendered from the new pose
    double pan_deg = 0.0;
    double tilt_deg = 0.0;
};

// A jump every 1-30 frames, 0-180 degrees from home split between pan and tilt (clamped
// to the +-90 degrees a head turns); seven in ten are a tenth that size, so that the hand
// is often still in view afterwards.
inline std::vector<RigJump> random_jumps(int frames, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> gap(1, 30);
    std::uniform_real_distribution<double> away(0.0, 180.0), share(0.0, 1.0), sign(-1.0, 1.0);
    std::vector<RigJump> jumps;
    for (int f = gap(rng); f < frames; f += gap(rng)) {
        const double size = away(rng) * (share(rng) < 0.7 ? 0.1 : 1.0), split = share(rng);
        jumps.push_back({f, std::clamp(sign(rng) * size * split, -90.0, 90.0),
                         std::clamp(sign(rng) * size * (1.0 - split), -90.0, 90.0)});
    }
    return jumps;
}

inline GstClockTime frame_time(int frame, int fps = kFps)
{
    return gst_util_uint64_scale(guint64(frame), GST_SECOND, guint64(fps));
}

// Sources `l` and `r`, tracker `t`, sink `sink`. With a head URI the sources are live and
// render from that head's pose, and the tracker reads it (steer off: it never moves it).
inline std::string pipeline_description(int frames, unsigned seed, const std::string& json_path,
                                        const std::string& head_uri = {}, int fps = kFps)
{
    const std::string head = head_uri.empty() ? "" : " head=" + head_uri;
    const std::string eye = " scene=light motion=mixed seed=" + std::to_string(seed) + " num-buffers=" +
                            std::to_string(frames) + (head_uri.empty() ? "" : " is-live=true") + head +
                            " ! video/x-raw,framerate=" + std::to_string(fps) + "/1 ! ";
    return "handscenesrc name=l eye=left" + eye + "t.sink_left handscenesrc name=r eye=right" + eye +
           "t.sink_right handtracker name=t steer=off message-updates=none json-location=" + json_path + head +
           " ! fakesink name=sink";
}

// Steps `property` of `element` to each jump's value at its frame's timestamp.
inline void drive(GstElement* element, const char* property, const std::vector<RigJump>& jumps, bool pan)
{
    GstControlSource* source = gst_interpolation_control_source_new();
    g_object_set(source, "mode", GST_INTERPOLATION_MODE_NONE, nullptr);
    auto* timed = GST_TIMED_VALUE_CONTROL_SOURCE(source);
    gst_timed_value_control_source_set(timed, 0, 0.0);
    for (const RigJump& j : jumps)
        gst_timed_value_control_source_set(timed, frame_time(j.frame), pan ? j.pan_deg : j.tilt_deg);
    gst_object_add_control_binding(GST_OBJECT(element),
                                   gst_direct_control_binding_new_absolute(GST_OBJECT(element), property, source));
    gst_object_unref(source);
}

inline bool drive_rig(GstElement* pipeline, const std::vector<RigJump>& jumps)
{
    for (const char* name : {"l", "r"}) {
        GstElement* src = gst_bin_get_by_name(GST_BIN(pipeline), name);
        if (!src) return false;
        drive(src, "head-pan", jumps, true);
        drive(src, "head-tilt", jumps, false);
        gst_object_unref(src);
    }
    return true;
}

struct EyeTruth {
    GstClockTime pts = GST_CLOCK_TIME_NONE;
    bool visible = false;
    int bbox[4] = {0, 0, 0, 0};
};

struct Run {
    bool eos = false;
    std::string error;
    std::vector<std::string> warnings;
    std::vector<EyeTruth> left, right;          // by frame
    std::vector<std::pair<int, long>> rss_kib;  // (output buffers so far, RSS) at the frames asked for
    double seconds = 0.0;
};

inline long rss_kib()
{
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return -1;
}

namespace detail {

struct Collector {
    std::mutex mutex;
    Run* run = nullptr;
    std::vector<int> rss_at;
    int buffers = 0;
};

// The truth messages are read as they are posted and dropped, so that the run's memory is
// the pipeline's, not a queue of 20 000 messages.
inline GstBusSyncReply keep_truth(GstBus*, GstMessage* msg, gpointer data)
{
    const GstStructure* s = gst_message_get_structure(msg);
    if (GST_MESSAGE_TYPE(msg) != GST_MESSAGE_ELEMENT || !s || !gst_structure_has_name(s, "hand-truth"))
        return GST_BUS_PASS;
    auto* c = static_cast<Collector*>(data);
    guint64 frame = 0;
    gboolean visible = FALSE;
    EyeTruth t;
    gst_structure_get_uint64(s, "frame", &frame);
    gst_structure_get_uint64(s, "timestamp", &t.pts);
    gst_structure_get_boolean(s, "visible", &visible);
    t.visible = visible;
    gst_structure_get(s, "bbox-x", G_TYPE_INT, &t.bbox[0], "bbox-y", G_TYPE_INT, &t.bbox[1], "bbox-width", G_TYPE_INT,
                      &t.bbox[2], "bbox-height", G_TYPE_INT, &t.bbox[3], nullptr);
    const bool left = std::string(gst_structure_get_string(s, "eye")) == "left";
    std::lock_guard<std::mutex> lock(c->mutex);
    std::vector<EyeTruth>& eye = left ? c->run->left : c->run->right;
    if (eye.size() <= frame) eye.resize(frame + 1);
    eye[frame] = t;
    gst_message_unref(msg);
    return GST_BUS_DROP;
}

inline GstPadProbeReturn count_output(GstPad*, GstPadProbeInfo*, gpointer data)
{
    auto* c = static_cast<Collector*>(data);
    ++c->buffers;
    if (std::find(c->rss_at.begin(), c->rss_at.end(), c->buffers) != c->rss_at.end())
        c->run->rss_kib.emplace_back(c->buffers, rss_kib());
    return GST_PAD_PROBE_OK;
}

}  // namespace detail

// Plays `pipeline` to EOS or an error, keeping the truth and the RSS after the output
// buffers numbered in `rss_at`.
inline Run play(GstElement* pipeline, const std::vector<int>& rss_at, GstClockTime timeout)
{
    Run run;
    detail::Collector collector;
    collector.run = &run;
    collector.rss_at = rss_at;
    GstBus* bus = gst_element_get_bus(pipeline);
    gst_bus_set_sync_handler(bus, detail::keep_truth, &collector, nullptr);
    GstElement* sink = gst_bin_get_by_name(GST_BIN(pipeline), "sink");
    GstPad* pad = gst_element_get_static_pad(sink, "sink");
    gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER, detail::count_output, &collector, nullptr);
    gst_object_unref(pad);
    gst_object_unref(sink);

    const GstClockTime started = gst_util_get_timestamp();
    if (gst_element_set_state(pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE)
        run.error = "state change to PLAYING failed";
    for (bool stop = !run.error.empty(); !stop;) {
        GstMessage* msg = gst_bus_timed_pop_filtered(
            bus, timeout, GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_WARNING));
        if (!msg) {
            run.error = "timeout";
            break;
        }
        GError* err = nullptr;
        if (GST_MESSAGE_TYPE(msg) == GST_MESSAGE_EOS) {
            run.eos = stop = true;
        } else if (GST_MESSAGE_TYPE(msg) == GST_MESSAGE_ERROR) {
            gst_message_parse_error(msg, &err, nullptr);
            run.error = err->message;
            stop = true;
        } else {
            gst_message_parse_warning(msg, &err, nullptr);
            run.warnings.emplace_back(err->message);
        }
        g_clear_error(&err);
        gst_message_unref(msg);
    }
    run.seconds = double(gst_util_get_timestamp() - started) / GST_SECOND;
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_bus_set_sync_handler(bus, nullptr, nullptr, nullptr);
    gst_object_unref(bus);
    return run;
}

// One JSON line's verdict: tracking, and where in the left view.
struct Tracked {
    bool line = false;  // a line was written for this frame
    bool tracking = false;
    int bbox[4] = {0, 0, 0, 0};
};

// The frame of `eye` taken at `pts` (within half a frame), or -1. A live source's frames
// start at the running time it was first asked for one, and a tracker may skip a frame.
inline int frame_at(const std::vector<EyeTruth>& eye, guint64 pts)
{
    if (eye.size() < 2 || !GST_CLOCK_TIME_IS_VALID(eye[0].pts) || !GST_CLOCK_TIME_IS_VALID(eye[1].pts)) return -1;
    const double frames = (double(pts) - double(eye[0].pts)) / double(eye[1].pts - eye[0].pts);
    const long frame = std::lround(frames);
    return frame >= 0 && size_t(frame) < eye.size() && std::abs(frames - double(frame)) < 0.5 ? int(frame) : -1;
}

// Whether the hand is in both views at the left eye's frame `f` (the right eye's frame
// taken at the same time).
inline bool visible_in_both(const Run& run, size_t f)
{
    if (!run.left[f].visible) return false;
    const int r = frame_at(run.right, run.left[f].pts);
    return r >= 0 && run.right[size_t(r)].visible;
}

// The tracker's lines ("pts_ns", "state" and the left eye's "bbox") by the left eye's frame.
inline std::vector<Tracked> read_tracked(const std::string& path, const Run& run)
{
    std::vector<Tracked> out;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        int counted = -1;
        unsigned long long pts = 0;
        if (std::sscanf(line.c_str(), "{\"frame\":%d,\"pts_ns\":%llu", &counted, &pts) != 2) continue;
        const int frame = frame_at(run.left, pts);
        if (frame < 0) continue;
        Tracked t;
        t.tracking = line.find("\"state\":\"tracking\"") != std::string::npos;
        const size_t left = line.find("\"left\":{");
        const size_t bbox = left == std::string::npos ? left : line.find("\"bbox\":[", left);
        if (bbox == std::string::npos || std::sscanf(line.c_str() + bbox, "\"bbox\":[%d,%d,%d,%d]", &t.bbox[0],
                                                     &t.bbox[1], &t.bbox[2], &t.bbox[3]) != 4)
            t.tracking = false;
        t.line = true;
        if (out.size() <= size_t(frame)) out.resize(size_t(frame) + 1);
        out[size_t(frame)] = t;
    }
    return out;
}

inline bool overlap(const int a[4], const int b[4])
{
    return a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3];
}

struct Outcome {
    int frame = 0;
    int visible_after = 0;  // consecutive frames from the jump with the hand in both views
    int found_after = -1;   // frames from the jump until tracked on the hand, -1: not within 60
    bool judged() const { return visible_after >= kJudgedVisibleFrames; }
    bool found() const { return found_after >= 0 && found_after <= kFoundWithin; }
};

// For every jump: how long the hand stayed in view and how soon the tracker had it again
// (tracking, its left box on the hand's), whatever later jumps did meanwhile.
inline std::vector<Outcome> judge(const std::vector<RigJump>& jumps, const Run& run,
                                  const std::vector<Tracked>& tracked)
{
    const size_t frames = std::min(run.left.size(), tracked.size());
    std::vector<Outcome> out;
    for (const RigJump& j : jumps) {
        Outcome o;
        o.frame = j.frame;
        for (size_t f = size_t(j.frame); f < frames && f - size_t(j.frame) < size_t(kJudgedVisibleFrames); ++f) {
            if (!visible_in_both(run, f)) break;
            ++o.visible_after;
            if (o.found_after < 0 && tracked[f].tracking && overlap(tracked[f].bbox, run.left[f].bbox))
                o.found_after = int(f) - j.frame;
        }
        out.push_back(o);
    }
    return out;
}

}  // namespace gc::chaos
