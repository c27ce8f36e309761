// The head-jump run with the head link, as an installation has it: a simulated head served on
// loopback, whose pose both handscenesrc eyes render from (live) and handtracker reads at each
// frame's capture, is moved to each jump's pose by a head client from a thread of its own,
// on the pipeline's clock. The head's axes are those of a fast PTZ camera, so that a jump of
// 180 degrees is over within three frames (a tenth of it within one).
#pragma once

#include "running_head.hpp"
#include "element_chaos.hpp"
#include "headctl/head_client.hpp"

#include <atomic>
#include <chrono>
#include <thread>

namespace gc::chaos {

// Pan and tilt through +-90 degrees, as the jumps reach; 180 degrees in 85 ms, 18 in 27 ms
// (1e5 deg/s^2 is the most GCHP carries).
inline headctl::HeadServerConfig fast_head()
{
    headctl::HeadServerConfig c = loopback::loopback_head(0, 0.0);
    for (headctl::Axis a : {headctl::Axis::Pan, headctl::Axis::Tilt})
        c.model.limits[a] = headctl::AxisLimits{-90.0, 90.0, 5000.0, 100000.0};
    return c;
}

// Sends each jump's absolute pose one frame before its frame's capture time, so that the
// move lands on that frame. The frames' capture times start at the first buffer of source
// `l` (a live source stamps it with the running time it was asked for).
class HeadJumper {
public:
    HeadJumper(GstElement* pipeline, std::vector<RigJump> jumps, const std::string& uri, int fps)
        : jumps_(std::move(jumps)), fps_(fps)
    {
        headctl::HeadClientConfig config;
        config.uri = uri;
        client_ = std::make_unique<headctl::HeadClient>(config);
        GstElement* src = gst_bin_get_by_name(GST_BIN(pipeline), "l");
        GstPad* pad = gst_element_get_static_pad(src, "src");
        gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER, first_buffer, this, nullptr);
        gst_object_unref(pad);
        gst_object_unref(src);
        pipeline_ = GST_ELEMENT(gst_object_ref(pipeline));
        thread_ = std::thread([this] { run(); });
    }
    ~HeadJumper()
    {
        stop_ = true;
        thread_.join();
        gst_object_unref(pipeline_);
    }
    HeadJumper(const HeadJumper&) = delete;
    HeadJumper& operator=(const HeadJumper&) = delete;

    int sent() const { return sent_; }

private:
    static GstPadProbeReturn first_buffer(GstPad*, GstPadProbeInfo* info, gpointer data)
    {
        static_cast<HeadJumper*>(data)->origin_ = GST_BUFFER_PTS(GST_PAD_PROBE_INFO_BUFFER(info));
        return GST_PAD_PROBE_REMOVE;
    }

    // The pipeline's running time, or none before it has a clock.
    GstClockTime running_time() const
    {
        GstClock* clock = gst_element_get_clock(pipeline_);
        if (!clock) return GST_CLOCK_TIME_NONE;
        const GstClockTime now = gst_clock_get_time(clock), base = gst_element_get_base_time(pipeline_);
        gst_object_unref(clock);
        return now > base ? now - base : 0;
    }

    void run()
    {
        using namespace std::chrono_literals;
        while (!stop_ && !GST_CLOCK_TIME_IS_VALID(origin_.load())) std::this_thread::sleep_for(2ms);
        for (const RigJump& j : jumps_) {
            const GstClockTime due = origin_ + frame_time(std::max(j.frame - 1, 0), fps_);
            for (GstClockTime now; !stop_ && (!GST_CLOCK_TIME_IS_VALID(now = running_time()) || now < due);)
                std::this_thread::sleep_for(2ms);
            if (stop_) return;
            headctl::HeadCommand move{headctl::CommandKind::Absolute, {}, 0};
            move.values.set(headctl::Axis::Pan, j.pan_deg);
            move.values.set(headctl::Axis::Tilt, j.tilt_deg);
            client_->submit(move);
            ++sent_;
        }
    }

    std::vector<RigJump> jumps_;
    int fps_;
    std::unique_ptr<headctl::HeadClient> client_;
    GstElement* pipeline_ = nullptr;
    std::atomic<GstClockTime> origin_{GST_CLOCK_TIME_NONE};
    std::atomic<bool> stop_{false};
    std::atomic<int> sent_{0};
    std::thread thread_;
};

}  // namespace gc::chaos
