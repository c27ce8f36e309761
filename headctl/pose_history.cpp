#include "headctl/pose_history.hpp"

#include <algorithm>
#include <stdexcept>

namespace gc::headctl {

namespace {
HeadPose lerp(const HeadPose& a, const HeadPose& b, double f)
{
    HeadPose p;
    for (Axis axis : kAllAxes) {
        const double va = axis_value(a, axis);
        set_axis_value(p, axis, va + (axis_value(b, axis) - va) * f);
    }
    return p;
}
}  // namespace

PoseHistory::PoseHistory(std::size_t capacity) : ring_(capacity)
{
    if (capacity < 2) throw std::invalid_argument("a pose history needs room for at least 2 samples");
}

const StateSample& PoseHistory::at(std::size_t i) const { return ring_[(head_ + i) % ring_.size()]; }

void PoseHistory::push(const StateSample& sample)
{
    if (count_ > 0 && sample.time <= at(count_ - 1).time) return;
    if (count_ < ring_.size()) {
        ring_[(head_ + count_) % ring_.size()] = sample;
        ++count_;
    } else {
        ring_[head_] = sample;
        head_ = (head_ + 1) % ring_.size();
    }
}

std::optional<StateSample> PoseHistory::newest() const
{
    if (count_ == 0) return std::nullopt;
    return at(count_ - 1);
}

std::optional<HeadPose> PoseHistory::pose_at(Timestamp t, Timestamp max_extrapolation) const
{
    if (count_ == 0) return std::nullopt;
    const StateSample& first = at(0);
    const StateSample& last = at(count_ - 1);
    if (t <= first.time) return first.state.pose;
    if (t >= last.time) {
        if (count_ < 2) return last.state.pose;
        const StateSample& prev = at(count_ - 2);
        const Timestamp ahead = std::min(t - last.time, std::max(max_extrapolation, Timestamp{0}));
        const double f = static_cast<double>(ahead.count()) / static_cast<double>((last.time - prev.time).count());
        HeadPose p = lerp(last.state.pose, lerp(prev.state.pose, last.state.pose, 2.0), f);
        // An axis the head reports at rest stays where it is.
        for (Axis axis : kAllAxes)
            if (!last.state.moving_axis(axis)) set_axis_value(p, axis, axis_value(last.state.pose, axis));
        return p;
    }
    // The first sample later than t; samples are strictly increasing in time.
    std::size_t lo = 1;
    std::size_t hi = count_ - 1;
    while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (at(mid).time > t)
            hi = mid;
        else
            lo = mid + 1;
    }
    const StateSample& a = at(lo - 1);
    const StateSample& b = at(lo);
    const double f = static_cast<double>((t - a.time).count()) / static_cast<double>((b.time - a.time).count());
    return lerp(a.state.pose, b.state.pose, f);
}

}  // namespace gc::headctl
