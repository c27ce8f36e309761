// Timestamped head states in a fixed-size ring, and the pose at any time between them.
#pragma once

#include "headctl/axes.hpp"

#include <chrono>
#include <optional>
#include <vector>

namespace gc::headctl {

// A time on the caller's clock (e.g. steady_clock's, or a pipeline's running time).
using Timestamp = std::chrono::nanoseconds;

// A timestamp in seconds, the unit the steering laws reckon in.
inline double to_seconds(Timestamp t) { return std::chrono::duration<double>(t).count(); }

struct StateSample {
    Timestamp time{0};
    HeadState state;
};

class PoseHistory {
public:
    explicit PoseHistory(std::size_t capacity);  // capacity >= 2

    // Samples must come in time order; one not later than the newest is dropped.
    void push(const StateSample& sample);
    std::size_t size() const { return count_; }
    std::optional<StateSample> newest() const;

    // The pose at t: interpolated between the samples around it; before the oldest, the
    // oldest; after the newest, the axes it reports moving are extrapolated along the last
    // two samples' velocity for at most max_extrapolation, then held. nullopt when empty.
    std::optional<HeadPose> pose_at(Timestamp t, Timestamp max_extrapolation) const;

private:
    const StateSample& at(std::size_t i) const;  // 0 = oldest

    std::vector<StateSample> ring_;
    std::size_t head_ = 0;  // index of the oldest
    std::size_t count_ = 0;
};

}  // namespace gc::headctl
