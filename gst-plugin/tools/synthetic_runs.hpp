// gesturecam-bench on the synthetic scenes: one eye's sequence rendered ahead of timing,
// our tracker run over it and scored against the scene's true masks (thesis Tables 4.1 and
// 4.2), and the cost of merely touching a frame, the yardstick the costs are divided by.
#pragma once

#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace gc::tools {

// One eye of one scene, rendered before anything is timed.
struct Sequence {
    std::vector<cv::Mat> frames;
    std::vector<cv::Mat1b> masks;
    std::vector<cv::Rect> boxes;
    std::vector<bool> visible;
    int first_visible = -1;
};

Sequence render_sequence(const gc::sim::Scene& scene, int frames, gc::Eye eye);

// Accuracy of one particle count on one scene, pooled over seeds.
struct AccuracyRow {
    gc::SnrAccumulator snr;
    double iou_sum = 0.0;
    std::int64_t iou_frames = 0;
    std::int64_t tracked = 0;
    std::int64_t visible = 0;
    std::int64_t lost = 0;
    std::vector<double> ms;        // per seed: the median over runs
    std::vector<double> cpu_ms;    // ... of the CPU time
    std::vector<int> acquired_at;  // per seed: first tracking frame, -1 never
};

// Per frame: the median over runs of the mean wall and CPU time.
struct TrackerCost {
    double ms = 0.0;
    double cpu_ms = 0.0;
};

// Runs our tracker over a sequence `runs` times; the first run is also scored. Only
// HandTracker::process is timed. `boxes`, when given, receives our per-frame box (empty
// when not tracking) from the first run.
TrackerCost run_tracker(const Sequence& seq, const gc::TrackerParams& params, int runs, AccuracyRow* row,
                        std::vector<cv::Rect>* boxes);

// Baseline: the cost of touching the frame once (a copy and a BGR -> RGB conversion).
struct Baseline {
    double copy_ms = 0.0;
    double convert_ms = 0.0;
};

Baseline measure_baseline(const Sequence& seq, int runs);

}  // namespace gc::tools
