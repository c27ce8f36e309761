// gesturecam-bench: the thesis's Tables 4.1 (accuracy) and 4.2 (cost) on the synthetic
// scenes for each hand detector, OpenCV's own trackers as peers on the same frames, the 3D
// step's cost, the stereo pipeline's throughput, one call of each learned model, and the
// real calibrated pair. Output: markdown tables, or JSON lines with --json (one object per
// line, "kind" says which table it belongs to; docs/benchmarks.md).
#include "tools/bench_options.hpp"
#include "tools/bench_report.hpp"
#include "tools/bench_stats.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

namespace {

using namespace gc::tools;

constexpr int kModelCalls = 20;  // timed calls of each model, each way

// Every detector and particle count and, unless --no-peers, the peers, on one scene over
// every seed.
void measure_scene(const BenchOptions& o, std::size_t si, BenchResults& r, std::vector<Baseline>& baselines)
{
    const std::string scene_name(gc::sim::to_string(o.scenes[si]));
    std::map<std::string, PeerScore> peer_scores;
    std::vector<double> skin_fraction;
    for (std::uint64_t seed : o.seeds) {
        gc::sim::SceneConfig config;
        config.preset = o.scenes[si];
        config.motion = o.motion;
        config.seed = seed;
        const gc::sim::Scene scene(config);
        std::cerr << "gesturecam-bench: " << scene_name << ", seed " << seed << '\n';
        const Sequence seq = render_sequence(scene, o.frames, gc::Eye::Left);
        skin_fraction.push_back(scene.measured_skin_fraction(0));
        baselines.push_back(measure_baseline(seq, o.runs));
        for (int di = 0; di < static_cast<int>(o.detectors.size()); ++di) {
            for (int particles : o.particles) {
                gc::TrackerParams params;
                params.particles = particles;
                params.seed = seed;
                params.detector = o.detectors[di];
                AccuracyRow& row = r.accuracy[{di, static_cast<int>(si), particles}];
                const TrackerCost cost = run_tracker(seq, params, o.runs, &row, nullptr);
                row.ms.push_back(cost.ms);
                row.cpu_ms.push_back(cost.cpu_ms);
            }
        }
        if (!o.peers) continue;
        gc::TrackerParams params;
        params.particles = o.peer_particles;
        params.seed = seed;
        params.detector = o.detectors.front();
        compare_with_peers(seq, params, scene_name + " seed " + std::to_string(seed), peer_scores);
    }
    r.skin_pct.push_back(100.0 * mean(skin_fraction));
    append_peer_rows(scene_name, peer_scores, r.peers);
}

int run_bench(const BenchOptions& o)
{
    std::error_code ec;
    if (o.real_dir_given && !o.real_dir.empty() && !std::filesystem::is_directory(o.real_dir, ec))
        throw std::runtime_error("--real: no folder " + o.real_dir);
    cv::setNumThreads(1);  // per-eye figures are single-threaded
    BenchResults r;
    r.machine = machine_info();
    std::vector<Baseline> baselines;
    for (std::size_t si = 0; si < o.scenes.size(); ++si) measure_scene(o, si, r, baselines);

    for (gc::HandDetector detector : o.detectors) {
        std::cerr << "gesturecam-bench: stereo, " << detector_name(detector) << '\n';
        r.stereo.push_back(measure_stereo(o, detector));
    }
    if (std::find(o.detectors.begin(), o.detectors.end(), gc::HandDetector::Learned) != o.detectors.end()) {
        std::cerr << "gesturecam-bench: learned models, one call\n";
        r.models = measure_models(kModelCalls);
    }
    r.real = measure_real_pair_rows(o);
    std::vector<double> copy_ms, convert_ms;
    for (const Baseline& b : baselines) {
        copy_ms.push_back(b.copy_ms);
        convert_ms.push_back(b.convert_ms);
    }
    r.baseline = {median(copy_ms), median(convert_ms)};
    print_report(o, r, std::cout);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    BenchOptions options;
    if (const int status = parse_bench_options(argc, argv, options); status >= 0) return status;
    try {
        return run_bench(options);
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-bench: error: " << e.what() << '\n';
        return 1;
    }
}
