// gesturecam-bench's output: markdown tables, or one JSON object per line whose "kind"
// names its table (docs/benchmarks.md lists the fields).
#pragma once

#include "tools/bench_options.hpp"
#include "tools/machine_info.hpp"
#include "tools/peer_runs.hpp"
#include "tools/stereo_runs.hpp"
#include "tools/synthetic_runs.hpp"

#include <map>
#include <ostream>
#include <utility>
#include <vector>

namespace gc::tools {

struct BenchResults {
    MachineInfo machine;
    Baseline baseline;                                // medians over every sequence
    std::map<std::pair<int, int>, AccuracyRow> accuracy;  // by (scene index, particles)
    std::vector<double> skin_pct;                     // per scene, mean over seeds
    std::vector<PeerRow> peers;
    StereoFigures stereo;
};

void print_report(const BenchOptions& o, const BenchResults& r, std::ostream& out);

}  // namespace gc::tools
