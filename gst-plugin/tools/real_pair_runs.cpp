#include "tools/real_pair_runs.hpp"

#include "tools/bench_stats.hpp"

#include <filesystem>
#include <iostream>

namespace gc::tools {

std::vector<RealPairRow> measure_real_pair_rows(const BenchOptions& o)
{
    std::vector<RealPairRow> rows;
    if (o.real_dir.empty()) return rows;
    std::error_code ec;
    if (!o.real_dir_given && !std::filesystem::is_directory(o.real_dir, ec)) {
        std::cerr << "gesturecam-bench: no real pair at " << o.real_dir << " (name its folder with --real); skipped\n";
        return rows;
    }
    RealPairOptions options;
    options.dir = o.real_dir;
    options.last_frame = o.real_frames;
    options.params.particles = o.peer_particles;
    options.params.seed = o.seeds.front();
    for (gc::HandDetector detector : o.detectors) {
        options.params.detector = detector;
        RealPairRow row;
        row.detector = detector;
        std::vector<double> ms, cpu_ms;
        for (int run = 0; run < o.runs; ++run) {
            std::cerr << "gesturecam-bench: real pair, " << detector_name(detector) << ", run " << run + 1 << '\n';
            const RealPairFigures f = measure_real_pair(options);
            if (run == 0) row.figures = f;
            ms.push_back(f.ms_per_frame);
            cpu_ms.push_back(f.cpu_ms_per_frame);
        }
        for (const NamedWindow& w : kEdgeWindows) {
            std::cerr << "gesturecam-bench: real pair, " << detector_name(detector) << ", " << w.name << '\n';
            RealCropOptions crop;
            crop.dir = options.dir;
            crop.camera = w.camera;
            crop.window = w.window;
            crop.last_frame = options.last_frame;
            crop.params = options.params;
            row.windows.push_back(measure_real_crop(crop));
        }
        row.ms_per_frame = median(ms);
        row.cpu_ms_per_frame = median(cpu_ms);
        rows.push_back(row);
    }
    return rows;
}

}  // namespace gc::tools
