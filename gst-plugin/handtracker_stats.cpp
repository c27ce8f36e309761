#include "handtracker_stats.hpp"

#include <algorithm>
#include <utility>

namespace gc::gst {

std::optional<GstClockTime> TrackerStats::frame_processed(GstClockTime took, bool tracked)
{
    std::lock_guard lock(mutex_);
    tracked_ += tracked ? 1 : 0;
    recent_.push_back(took);
    if (recent_.size() > kWindow) recent_.pop_front();
    // Whole milliseconds. A longer frame raises the latency at once, never under-reporting it,
    // with a quarter's headroom so that a slowly growing maximum does not post a latency
    // message on every frame; it comes down only when the longest took under three quarters.
    const GstClockTime longest = *std::max_element(recent_.begin(), recent_.end());
    const auto whole_ms = [](GstClockTime t) { return (t + GST_MSECOND - 1) / GST_MSECOND * GST_MSECOND; };
    const GstClockTime latency = whole_ms(longest);
    if (latency > reported_) {
        reported_ = whole_ms(longest + longest / 4);
        return reported_;
    }
    if (latency * 4 < reported_ * 3) {
        reported_ = latency;
        return latency;
    }
    return std::nullopt;
}

void TrackerStats::frame_skipped()
{
    std::lock_guard lock(mutex_);
    ++skipped_;
    ++skipped_since_line_;
}

guint64 TrackerStats::take_skipped_since_line()
{
    std::lock_guard lock(mutex_);
    return std::exchange(skipped_since_line_, 0);
}

guint64 TrackerStats::skipped() const
{
    std::lock_guard lock(mutex_);
    return skipped_;
}

GstStructure* TrackerStats::to_structure() const
{
    std::lock_guard lock(mutex_);
    const GstClockTime longest = recent_.empty() ? 0 : *std::max_element(recent_.begin(), recent_.end());
    return gst_structure_new("application/x-handtracker-stats", "tracked", G_TYPE_UINT64, tracked_, "skipped-qos",
                             G_TYPE_UINT64, skipped_, "processing-time-max", G_TYPE_UINT64, longest, "latency",
                             G_TYPE_UINT64, reported_, nullptr);
}

void TrackerStats::reset()
{
    std::lock_guard lock(mutex_);
    tracked_ = skipped_ = skipped_since_line_ = 0;
    recent_.clear();
    reported_ = 0;
}

}  // namespace gc::gst
