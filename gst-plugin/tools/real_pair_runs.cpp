#include "tools/real_pair_runs.hpp"

#include "tools/bench_stats.hpp"

#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <stdexcept>

namespace gc::tools {

namespace {

// The first of `items`, with each of `fields` set to its mean over all of them.
template <typename T>
T mean_of_fields(const std::vector<T>& items, std::initializer_list<double T::*> fields)
{
    T mean = items.front();
    for (double T::*field : fields) {
        double sum = 0.0;
        for (const T& item : items) sum += item.*field;
        mean.*field = sum / double(items.size());
    }
    return mean;
}

// The view `part` of every item.
template <typename T>
std::vector<ViewFigures> views_of(const std::vector<T>& items, ViewFigures T::*part)
{
    std::vector<ViewFigures> views;
    for (const T& item : items) views.push_back(item.*part);
    return views;
}

ViewFigures mean_view(const std::vector<ViewFigures>& views)
{
    return mean_of_fields(views,
                          {&ViewFigures::coverage, &ViewFigures::within_30px, &ViewFigures::median_px,
                           &ViewFigures::median_px_models, &ViewFigures::median_px_carried, &ViewFigures::models_share,
                           &ViewFigures::pointing_coverage, &ViewFigures::pointing_median_px});
}

RealCropFigures measure_window(const RealPairOptions& options, const NamedWindow& w)
{
    RealCropOptions crop = window_options(options.dir, w);
    crop.last_frame = options.last_frame;
    crop.params = options.params;
    crop.noise_sd = options.noise_sd;
    crop.dim = options.dim;
    return measure_real_crop(crop);
}

}  // namespace

RealPairFigures mean_figures(const std::vector<RealPairFigures>& per_seed)
{
    if (per_seed.empty()) throw std::invalid_argument("mean_figures: no figures to average");
    RealPairFigures m = mean_of_fields(per_seed, {&RealPairFigures::ray_coverage, &RealPairFigures::angle_median_deg,
                                                  &RealPairFigures::angle_p90_deg, &RealPairFigures::false_pointing,
                                                  &RealPairFigures::ms_per_frame, &RealPairFigures::cpu_ms_per_frame});
    m.left = mean_view(views_of(per_seed, &RealPairFigures::left));
    m.right = mean_view(views_of(per_seed, &RealPairFigures::right));
    return m;
}

RealCropFigures mean_figures(const std::vector<RealCropFigures>& per_seed)
{
    if (per_seed.empty()) throw std::invalid_argument("mean_figures: no figures to average");
    RealCropFigures m = per_seed.front();
    m.view = mean_view(views_of(per_seed, &RealCropFigures::view));
    return m;
}

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
    options.noise_sd = o.real_noise;
    options.dim = o.real_dim;
    options.bright_window = o.real_bright_window;
    options.params.particles = o.peer_particles;
    options.params.tracking_width = o.real_tracking_width;
    for (gc::HandDetector detector : o.detectors) {
        options.params.detector = detector;
        RealPairRow row;
        row.detector = detector;
        std::vector<RealPairFigures> per_seed;
        std::vector<std::vector<RealCropFigures>> windows(std::size(kEdgeWindows));
        std::vector<double> ms, cpu_ms;
        for (std::uint64_t seed : o.seeds) {
            options.params.seed = seed;
            for (int run = 0; run < o.runs; ++run) {
                std::cerr << "gesturecam-bench: real pair, " << detector_name(detector) << ", seed " << seed << ", run "
                          << run + 1 << '\n';
                const RealPairFigures f = measure_real_pair(options);
                if (run == 0) per_seed.push_back(f);
                ms.push_back(f.ms_per_frame);
                cpu_ms.push_back(f.cpu_ms_per_frame);
            }
            for (std::size_t i = 0; i < std::size(kEdgeWindows); ++i) {
                std::cerr << "gesturecam-bench: real pair, " << detector_name(detector) << ", seed " << seed << ", "
                          << kEdgeWindows[i].name << '\n';
                windows[i].push_back(measure_window(options, kEdgeWindows[i]));
            }
        }
        row.figures = mean_figures(per_seed);
        for (const std::vector<RealCropFigures>& w : windows) row.windows.push_back(mean_figures(w));
        row.ms_per_frame = median(ms);
        row.cpu_ms_per_frame = median(cpu_ms);
        rows.push_back(row);
    }
    return rows;
}

}  // namespace gc::tools
