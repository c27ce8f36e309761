// gesturecam-bench on the real calibrated pair (tests/data/handpose3d): each detector's
// figures against the reference key points (in stereo, and one view through windows its
// hand enters from the edge of), and its cost timed over --runs runs.
#pragma once

#include "tools/bench_options.hpp"
#include "tools/real_pair.hpp"

#include <vector>

namespace gc::tools {

struct RealPairRow {
    gc::HandDetector detector = gc::HandDetector::Learned;
    RealPairFigures figures;               // of the first run (the runs track alike)
    std::vector<RealCropFigures> windows;  // one per kEdgeWindows, the view tracked alone
    double ms_per_frame = 0.0;             // median over runs of each run's median stereo frame
    double cpu_ms_per_frame = 0.0;         // ... of its CPU time
};

// One row per detector of `o`; none when the real pair is skipped, or when the source
// tree's copy is missing and no --real named a folder (said on stderr). Throws
// std::runtime_error when a named folder cannot be read.
std::vector<RealPairRow> measure_real_pair_rows(const BenchOptions& o);

}  // namespace gc::tools
