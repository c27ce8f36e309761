// gesturecam-bench on the real calibrated pair (tests/data/handpose3d): each detector's
// figures against the reference key points (in stereo, and one view through windows its
// hand enters from the edge of), each the mean of its per-seed figures over --seeds (one
// seed's figures move with the tracker's random path alone: docs/benchmarks.md), and its
// cost timed over --runs runs of each seed.
#pragma once

#include "tools/bench_options.hpp"
#include "tools/real_pair.hpp"

#include <vector>

namespace gc::tools {

struct RealPairRow {
    gc::HandDetector detector = gc::HandDetector::Learned;
    RealPairFigures figures;               // of each seed's first run (a seed's runs track alike)
    std::vector<RealCropFigures> windows;  // one per kEdgeWindows, the view tracked alone
    double ms_per_frame = 0.0;             // median over all runs of each run's median stereo frame
    double cpu_ms_per_frame = 0.0;         // ... of its CPU time
};

// The mean of per-seed figures, field by field; counts of frames are the first's (every seed
// tracks the same frames). Throws std::invalid_argument when `per_seed` is empty.
RealPairFigures mean_figures(const std::vector<RealPairFigures>& per_seed);
RealCropFigures mean_figures(const std::vector<RealCropFigures>& per_seed);

// One row per detector of `o`; none when the real pair is skipped, or when the source
// tree's copy is missing and no --real named a folder (said on stderr). Throws
// std::runtime_error when a named folder cannot be read.
std::vector<RealPairRow> measure_real_pair_rows(const BenchOptions& o);

}  // namespace gc::tools
