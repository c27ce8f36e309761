// gesturecam-bench's output: markdown tables, or one JSON object per line whose "kind"
// names its table (docs/benchmarks.md lists the fields).
#pragma once

#include "tools/bench_options.hpp"
#include "tools/machine_info.hpp"
#include "tools/model_runs.hpp"
#include "tools/peer_runs.hpp"
#include "tools/real_pair_runs.hpp"
#include "tools/stereo_runs.hpp"
#include "tools/synthetic_runs.hpp"

#include <map>
#include <ostream>
#include <tuple>
#include <vector>

namespace gc::tools {

struct BenchResults {
    MachineInfo machine;
    Baseline baseline;  // medians over every sequence
    // By (detector index, scene index, particles), the indices into o.detectors, o.scenes.
    std::map<std::tuple<int, int, int>, AccuracyRow> accuracy;
    std::vector<double> skin_pct;       // per scene, mean over seeds
    std::vector<PeerRow> peers;         // ours with o.detectors.front()
    std::vector<StereoFigures> stereo;  // one per detector
    std::vector<RealPairRow> real;      // one per detector, or none
    std::vector<ModelTiming> models;    // with the learned detector only
};

void print_report(const BenchOptions& o, const BenchResults& r, std::ostream& out);

// The seeds as the reports name them: "1,2,3".
std::string seeds_text(const std::vector<std::uint64_t>& seeds);

// The real pair's tables (real_pair_report.cpp).
void print_real_pair(const BenchOptions& o, const std::vector<RealPairRow>& rows, std::ostream& out);

}  // namespace gc::tools
