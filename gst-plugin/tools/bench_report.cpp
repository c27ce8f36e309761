#include "tools/bench_report.hpp"

#include "tools/bench_stats.hpp"
#include "tools/json_writer.hpp"

#include <opencv2/core/version.hpp>

#include <cmath>
#include <string>

namespace gc::tools {

std::string seeds_text(const std::vector<std::uint64_t>& seeds)
{
    std::string text;
    for (std::uint64_t s : seeds) {
        if (!text.empty()) text += ',';
        text += std::to_string(s);
    }
    return text;
}

namespace {

void print_header(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    const MachineInfo& m = r.machine;
    if (o.json) {
        out << JsonObject()
                   .add("kind", "machine")
                   .add("cores", static_cast<int>(m.cores))
                   .add("cpu", m.cpu_model)
                   .add("load_1min", m.load_1min, 2)
                   .add("opencv", CV_VERSION)
                   .add("width", 640)
                   .add("height", 480)
                   .add("frames", o.frames)
                   .add("runs", o.runs)
                   .add("seeds", seeds_text(o.seeds))
                   .add("motion", gc::sim::to_string(o.motion))
                   .str()
            << '\n';
        out << JsonObject()
                   .add("kind", "baseline")
                   .add("copy_ms", r.baseline.copy_ms, 4)
                   .add("convert_ms", r.baseline.convert_ms, 4)
                   .str()
            << '\n';
        return;
    }
    out << "# gesturecam-bench\n\n"
        << "machine: " << m.cores << " cores, " << m.cpu_model << ", load average " << fixed(m.load_1min, 2)
        << " at start\n"
        << "OpenCV " << CV_VERSION << ", one OpenCV thread; 640x480, " << o.frames << " frames per sequence, motion "
        << gc::sim::to_string(o.motion) << ", seeds " << seeds_text(o.seeds) << ", median of " << o.runs << " run(s)\n"
        << "baseline per frame: copy " << fixed(r.baseline.copy_ms, 3) << " ms, BGR->RGB conversion "
        << fixed(r.baseline.convert_ms, 3) << " ms\n\n";
}

// One row of Tables 4.1/4.2: one detector, scene and particle count.
void print_accuracy_row(const BenchOptions& o, const BenchResults& r, int di, int si, int particles, std::ostream& out)
{
    const std::string_view scene_name = gc::sim::to_string(o.scenes[si]);
    const double skin_pct = r.skin_pct[si];
    const AccuracyRow& a = r.accuracy.at({di, si, particles});
    const double iou = a.iou_frames > 0 ? a.iou_sum / a.iou_frames : std::nan("");
    const double tracked = a.visible > 0 ? static_cast<double>(a.tracked) / a.visible : 0.0;
    const double lost = static_cast<double>(a.lost) / o.seeds.size();
    const double ms = mean(a.ms);
    if (o.json) {
        out << JsonObject()
                   .add("kind", "tracker")
                   .add("scene", scene_name)
                   .add("detector", detector_name(o.detectors[di]))
                   .add("skin_pct", skin_pct, 2)
                   .add("particles", particles)
                   .add("snr_db", a.snr.snr_db(), 2)
                   .add("mean_iou", iou, 3)
                   .add("tracked_fraction", tracked, 3)
                   .add("lost_frames", lost, 1)
                   .add("ms_per_frame", ms, 3)
                   .add("cpu_ms_per_frame", mean(a.cpu_ms), 3)
                   .str()
            << '\n';
        return;
    }
    out << "| " << scene_name << " | " << fixed(skin_pct, 2) << " | " << particles << " | " << fixed(a.snr.snr_db(), 2)
        << " | " << fixed(iou, 3) << " | " << fixed(tracked, 3) << " | " << fixed(lost, 1) << " | " << fixed(ms, 2)
        << " | " << fixed(ms / r.baseline.convert_ms, 1) << " |\n";
}

// Tables 4.1/4.2 by particle count, one table per detector.
void print_accuracy(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    if (!o.json)
        out << "## Accuracy and cost by particle count (thesis Tables 4.1, 4.2)\n\n"
            << "ms/frame/eye is one OpenCV thread's time: the learned models' network runs on "
               "that one thread too, where the element would spread its layers over every core.\n";
    for (int di = 0; di < static_cast<int>(o.detectors.size()); ++di) {
        if (!o.json)
            out << "\n### " << detector_name(o.detectors[di]) << " detector\n\n"
                << "| scene | skin % | particles | SNR dB | mean IoU | tracked | lost frames | "
                   "ms/frame/eye | x conversion |\n"
                << "|---|---|---|---|---|---|---|---|---|\n";
        for (int si = 0; si < static_cast<int>(o.scenes.size()); ++si)
            for (int particles : o.particles) print_accuracy_row(o, r, di, si, particles, out);
    }
}

void print_peers(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    if (!o.json && !r.peers.empty())
        out << "\n## OpenCV trackers on the same frames (box IoU vs the true box; ours at " << o.peer_particles
            << " particles, " << detector_name(o.detectors.front()) << " detector)\n\n"
            << "| scene | tracker | box IoU | ms/frame | frames scored |\n|---|---|---|---|---|\n";
    for (const PeerRow& p : r.peers) {
        if (o.json)
            out << JsonObject()
                       .add("kind", "peer")
                       .add("scene", p.scene)
                       .add("tracker", p.tracker)
                       .add("particles", o.peer_particles)
                       .add("detector", detector_name(o.detectors.front()))
                       .add("box_iou", p.iou, 3)
                       .add("ms_per_frame", p.ms, 3)
                       .add("frames", p.frames)
                       .str()
                << '\n';
        else
            out << "| " << p.scene << " | " << p.tracker << " | " << fixed(p.iou, 3) << " | " << fixed(p.ms, 2) << " | "
                << p.frames << " |\n";
    }
}

void print_stereo(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    if (!o.json)
        out << "\n## Stereo (clean scene, " << o.peer_particles << " particles per eye)\n\n"
            << "| detector | 3D step ms/stereo frame | 3D valid frames | median direction error deg | "
               "median palm error mm | pipeline frames/s (2 threads) | CPU ms/stereo frame | "
               "with rendering frames/s | with rendering CPU ms/stereo frame | network share |\n"
            << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const StereoFigures& s : r.stereo) {
        if (o.json) {
            out << JsonObject()
                       .add("kind", "stereo")
                       .add("scene", "clean")
                       .add("detector", detector_name(s.detector))
                       .add("particles", o.peer_particles)
                       .add("frames", s.frames)
                       .add("valid_3d", s.valid)
                       .add("estimate_ms", s.estimate_ms, 3)
                       .add("direction_error_deg", s.direction_error_deg, 2)
                       .add("palm_error_mm", s.palm_error_mm, 1)
                       .add("pipeline_fps", s.fps, 2)
                       .add("threads", 2)
                       .add("cpu_ms_per_frame", s.cpu_ms, 2)
                       .add("rendering_fps", s.rendering_fps, 2)
                       .add("rendering_cpu_ms_per_frame", s.rendering_cpu_ms, 2)
                       .add("models_share", s.models_share, 3)
                       .str()
                << '\n';
            continue;
        }
        out << "| " << detector_name(s.detector) << " | " << fixed(s.estimate_ms, 2) << " | " << s.valid << "/"
            << s.frames << " | " << fixed(s.direction_error_deg, 1) << " | " << fixed(s.palm_error_mm, 0) << " | "
            << fixed(s.fps, 1) << " | " << fixed(s.cpu_ms, 2) << " | " << fixed(s.rendering_fps, 1) << " | "
            << fixed(s.rendering_cpu_ms, 2) << " | " << fixed(s.models_share, 3) << " |\n";
    }
}

void print_models(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    if (!o.json && !r.models.empty())
        out << "\n## Learned models, CPU ms per call (one thread, median of " << r.models.front().calls
            << " alternating calls)\n\n"
            << "| model | input | OpenCV's layers | with the product's depthwise convolution | ratio | "
               "largest output difference |\n|---|---|---|---|---|---|\n";
    for (const ModelTiming& m : r.models) {
        const double ratio = m.opencv_ms / m.product_ms;
        if (o.json) {
            out << JsonObject()
                       .add("kind", "models")
                       .add("model", m.model)
                       .add("input_side", m.input_side)
                       .add("calls", m.calls)
                       .add("opencv_cpu_ms", m.opencv_ms, 3)
                       .add("product_cpu_ms", m.product_ms, 3)
                       .add("ratio", ratio, 2)
                       .add("max_abs_diff", m.max_abs_diff, 6)
                       .str()
                << '\n';
            continue;
        }
        out << "| " << m.model << " | " << m.input_side << "x" << m.input_side << " | " << fixed(m.opencv_ms, 2)
            << " | " << fixed(m.product_ms, 2) << " | " << fixed(ratio, 2) << " | " << m.max_abs_diff << " |\n";
    }
}

}  // namespace

void print_report(const BenchOptions& o, const BenchResults& r, std::ostream& out)
{
    print_header(o, r, out);
    print_accuracy(o, r, out);
    print_peers(o, r, out);
    print_stereo(o, r, out);
    print_models(o, r, out);
    print_real_pair(o, r.real, out);
}

}  // namespace gc::tools
