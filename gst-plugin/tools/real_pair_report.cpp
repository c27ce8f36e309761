// gesturecam-bench's tables for the real pair: per view (fingertip against the reference,
// and on which frames the learned models looked), and in 3D (the pointing ray and the cost);
// each figure the mean of the per-seed figures.
#include "tools/bench_report.hpp"
#include "tools/bench_stats.hpp"
#include "tools/json_writer.hpp"

#include <string>

namespace gc::tools {

namespace {

// The fields every real row starts with: what was measured and how its frames were changed
// (the bright window is painted into the pair's views only, not into the windows', and only
// the pair's views are tracked at a smaller width).
JsonObject real_row(std::string_view kind, const BenchOptions& o, const RealPairRow& row, bool pair_views)
{
    const bool bright_window = pair_views && o.real_bright_window;
    JsonObject j;
    j.add("kind", kind)
        .add("detector", detector_name(row.detector))
        .add("seeds", seeds_text(o.seeds))
        .add("noise_sd", o.real_noise, 1)
        .add("dim", o.real_dim, 2)
        .add("bright_window", bright_window)
        .add("tracking_width", pair_views ? o.real_tracking_width : 0);
    return j;
}

void print_view(const BenchOptions& o, const RealPairRow& row, std::string_view view, const ViewFigures& v,
                std::ostream& out)
{
    if (o.json) {
        out << real_row("real_view", o, row, true)
                   .add("view", view)
                   .add("reference_frames", v.reference_frames)
                   .add("coverage", v.coverage, 3)
                   .add("within_30px", v.within_30px, 3)
                   .add("median_px", v.median_px, 1)
                   .add("median_px_models", v.median_px_models, 1)
                   .add("median_px_carried", v.median_px_carried, 1)
                   .add("models_share", v.models_share, 3)
                   .add("pointing_frames", v.pointing_frames)
                   .add("pointing_coverage", v.pointing_coverage, 3)
                   .add("pointing_median_px", v.pointing_median_px, 1)
                   .str()
            << '\n';
        return;
    }
    out << "| " << detector_name(row.detector) << " | " << view << " | " << v.reference_frames << " | "
        << fixed(v.coverage, 3) << " | " << fixed(v.within_30px, 3) << " | " << fixed(v.median_px, 1) << " | "
        << fixed(v.median_px_models, 1) << " | " << fixed(v.median_px_carried, 1) << " | " << fixed(v.models_share, 3)
        << " | " << v.pointing_frames << " | " << fixed(v.pointing_coverage, 3) << " | "
        << fixed(v.pointing_median_px, 1) << " |\n";
}

void print_3d(const BenchOptions& o, const RealPairRow& row, std::ostream& out)
{
    const RealPairFigures& f = row.figures;
    const double fps = row.ms_per_frame > 0.0 ? 1000.0 / row.ms_per_frame : std::nan("");
    if (o.json) {
        out << real_row("real_pair", o, row, true)
                   .add("particles", o.peer_particles)
                   .add("frames", f.frames)
                   .add("pointing_frames", f.pointing_frames)
                   .add("ray_coverage", f.ray_coverage, 3)
                   .add("angle_median_deg", f.angle_median_deg, 1)
                   .add("angle_p90_deg", f.angle_p90_deg, 1)
                   .add("other_frames", f.other_frames)
                   .add("false_pointing", f.false_pointing, 3)
                   .add("ms_per_frame", row.ms_per_frame, 2)
                   .add("cpu_ms_per_frame", row.cpu_ms_per_frame, 2)
                   .add("runs", o.runs)
                   .str()
            << '\n';
        return;
    }
    out << "| " << detector_name(row.detector) << " | " << f.pointing_frames << " | " << fixed(f.ray_coverage, 3)
        << " | " << fixed(f.angle_median_deg, 1) << " | " << fixed(f.angle_p90_deg, 1) << " | " << f.other_frames
        << " | " << fixed(f.false_pointing, 3) << " | " << fixed(row.ms_per_frame, 2) << " | " << fixed(fps, 1) << " | "
        << fixed(row.cpu_ms_per_frame, 2) << " |\n";
}

void print_windows(const BenchOptions& o, const std::vector<RealPairRow>& rows, std::ostream& out)
{
    if (!o.json)
        out << "\nOne view tracked alone through a narrower window (scaled to 640x480) whose edge the hand "
               "enters from; \"cut\" frames have reference key points outside the window:\n\n"
            << "| detector | window | reference frames | cut | tracked | within 30 px | median px | "
               "models share of tracked |\n"
            << "|---|---|---|---|---|---|---|---|\n";
    for (const RealPairRow& row : rows)
        for (std::size_t i = 0; i < row.windows.size() && i < std::size(kEdgeWindows); ++i) {
            const RealCropFigures& w = row.windows[i];
            if (o.json) {
                out << real_row("real_window", o, row, false)
                           .add("window", kEdgeWindows[i].name)
                           .add("reference_frames", w.view.reference_frames)
                           .add("cut_frames", w.cut_frames)
                           .add("coverage", w.view.coverage, 3)
                           .add("within_30px", w.view.within_30px, 3)
                           .add("median_px", w.view.median_px, 1)
                           .add("models_share", w.view.models_share, 3)
                           .str()
                    << '\n';
                continue;
            }
            out << "| " << detector_name(row.detector) << " | " << kEdgeWindows[i].name << " | "
                << w.view.reference_frames << " | " << w.cut_frames << " | " << fixed(w.view.coverage, 3) << " | "
                << fixed(w.view.within_30px, 3) << " | " << fixed(w.view.median_px, 1) << " | "
                << fixed(w.view.models_share, 3) << " |\n";
        }
}

}  // namespace

void print_real_pair(const BenchOptions& o, const std::vector<RealPairRow>& rows, std::ostream& out)
{
    if (rows.empty()) return;
    if (!o.json)
        out << "\n## Real pair (" << o.real_dir << ": 720x720, " << rows.front().figures.frames << " stereo frames, "
            << o.peer_particles << " particles per eye, seeds " << seeds_text(o.seeds)
            << (o.real_dim < 1.0 ? ", dimmed to " + fixed(o.real_dim, 2) : "")
            << (o.real_bright_window ? ", a bright window in view" : "")
            << (o.real_noise > 0.0 ? ", camera noise of " + fixed(o.real_noise, 1) + " grey levels added" : "")
            << (o.real_tracking_width > 0
                    ? ", tracked " + std::to_string(o.real_tracking_width) + " pixels wide (not the windows)"
                    : "")
            << ")\n\n"
            << "Each figure is the mean of the per-seed figures: one seed's move with the tracker's random "
               "path alone.\n\n"
            << "Fingertip against the reference key points, per view; \"models\" are the frames "
               "where the learned models ran, \"carried\" those the contour carried alone.\n\n"
            << "| detector | view | reference frames | tracked | within 30 px | median px | "
               "median px, models | median px, carried | models share of tracked | "
               "pointing frames | tracked while pointing | median px while pointing |\n"
            << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RealPairRow& row : rows) {
        print_view(o, row, "left", row.figures.left, out);
        print_view(o, row, "right", row.figures.right, out);
    }
    if (!o.json)
        out << "\nThe 3D pointing ray against the reference's, and the cost (median of " << o.runs
            << " run(s) of each seed; both eyes on two threads, one OpenCV thread each):\n\n"
            << "| detector | pointing frames | 3D ray | median angle deg | p90 angle deg | "
               "other frames | false pointing | ms/stereo frame | stereo frames/s | "
               "CPU ms/stereo frame |\n"
            << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RealPairRow& row : rows) print_3d(o, row, out);
    print_windows(o, rows, out);
}

}  // namespace gc::tools
