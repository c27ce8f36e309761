// What handtracker counts while it runs, for the `stats` property (read from any thread): the
// frames it tracked, the output frames GstVideoAggregator dropped under QoS (downstream said
// they would come too late), and the time it spends on a frame, which it adds to the latency
// it reports.
#pragma once

#include <gst/gst.h>

#include <deque>
#include <mutex>
#include <optional>

namespace gc::gst {

class TrackerStats {
public:
    // One output frame made in `took`; returns the processing latency to report when it changed
    // by more than a quarter (the longest of the last kWindow frames), otherwise nothing.
    std::optional<GstClockTime> frame_processed(GstClockTime took, bool tracked);
    // GstVideoAggregator dropped an output frame under QoS: no meta, no message, no JSON line.
    void frame_skipped();
    // The frames skipped since the last call (they are named on the next JSON line).
    guint64 take_skipped_since_line();
    guint64 skipped() const;
    // application/x-handtracker-stats: tracked, skipped-qos, processing-time-max, latency.
    GstStructure* to_structure() const;
    void reset();

    static constexpr size_t kWindow = 30;

private:
    mutable std::mutex mutex_;
    guint64 tracked_ = 0;
    guint64 skipped_ = 0;
    guint64 skipped_since_line_ = 0;
    std::deque<GstClockTime> recent_;  // processing times of the last kWindow frames
    GstClockTime reported_ = 0;
};

}  // namespace gc::gst
