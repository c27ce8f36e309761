// gesturecam-bench: the thesis's Tables 4.1 (accuracy) and 4.2 (cost) on the synthetic
// scenes, OpenCV's own trackers as peers on the same frames, the 3D step's cost and the
// stereo pipeline's throughput. Output: markdown tables, or JSON lines with --json
// (one object per line, "kind" says which table it belongs to; docs/benchmarks.md).
#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "stereo/pointing.hpp"
#include "tools/cli_args.hpp"
#include "tools/json_writer.hpp"
#include "tools/machine_info.hpp"
#include "tools/peer_trackers.hpp"
#include "tracker/hand_tracker.hpp"
#include "tracker/pointing_tracker.hpp"
#include "tracker/stereo_tracker.hpp"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kUsage = R"(usage: gesturecam-bench [options]

Measures the tracker on the synthetic scenes (640x480): SNR, mean mask IoU, tracked fraction,
lost frames and milliseconds per frame per eye by particle count; OpenCV's trackers (KCF,
CSRT, MedianFlow, CamShift) on the same frames; the 3D step; the stereo throughput.

options:
  --particles LIST   particle counts (default 20,50,100,200,500,1000,2000,5000)
  --scenes LIST      clean,light,heavy,face_pass (default: all four)
  --motion NAME      scripted hand motion: static, translate, rotate, scale, yaw, mixed,
                     leave_return (default mixed)
  --frames N         frames per sequence (default 150)
  --runs R           timed runs per measurement; the median is reported (default 5)
  --seeds LIST       scene seeds; figures are pooled over them (default 1,2,3)
  --peer-particles N our particle count in the comparison with OpenCV's trackers, the 3D
                     step and the throughput (default 1000)
  --no-peers         skip the comparison with OpenCV's trackers
  --quick            a small smoke run: particles 50,200, scenes clean,heavy, 40 frames,
                     1 run, seed 1, 200 particles for the comparisons (options given
                     explicitly still apply)
  --json             JSON lines instead of markdown tables
  --help             this text
)";

struct Options {
    std::vector<int> particles{20, 50, 100, 200, 500, 1000, 2000, 5000};
    std::vector<gc::sim::Preset> scenes{gc::sim::Preset::Clean, gc::sim::Preset::Light,
                                        gc::sim::Preset::Heavy, gc::sim::Preset::FacePass};
    gc::sim::Motion motion = gc::sim::Motion::Mixed;
    int frames = 150;
    int runs = 5;
    std::vector<std::uint64_t> seeds{1, 2, 3};
    int peer_particles = 1000;
    bool peers = true;
    bool json = false;
    bool help = false;
};

Options parse_options(int argc, char** argv)
{
    using gc::cli::parse_number;
    Options o;
    gc::cli::ArgReader args(argc, argv);
    bool quick = false;
    std::optional<std::vector<int>> particles;
    std::optional<std::vector<gc::sim::Preset>> scenes;
    std::optional<int> frames, runs, peer_particles;
    std::optional<std::vector<std::uint64_t>> seeds;
    while (args.next()) {
        const std::string_view name = args.name();
        if (name == "--help") {
            args.no_value();
            o.help = true;
        } else if (name == "--json") {
            args.no_value();
            o.json = true;
        } else if (name == "--quick") {
            args.no_value();
            quick = true;
        } else if (name == "--no-peers") {
            args.no_value();
            o.peers = false;
        } else if (name == "--particles") {
            particles = gc::cli::parse_list<int>(name, args.value(), [](auto opt, auto item) {
                return parse_number<int>(opt, item, 1, 100000);
            });
        } else if (name == "--scenes") {
            scenes = gc::cli::parse_list<gc::sim::Preset>(name, args.value(), [](auto opt, auto item) {
                const auto p = gc::sim::preset_from_string(item);
                if (!p)
                    throw gc::cli::UsageError(std::string(opt) + ": unknown scene '" +
                                              std::string(item) +
                                              "' (clean, light, heavy, face_pass)");
                return *p;
            });
        } else if (name == "--motion") {
            const std::string_view v = args.value();
            const auto m = gc::sim::motion_from_string(v);
            if (!m)
                throw gc::cli::UsageError("--motion: unknown motion '" + std::string(v) + "'");
            o.motion = *m;
        } else if (name == "--frames") {
            frames = parse_number<int>(name, args.value(), 10, 100000);
        } else if (name == "--runs") {
            runs = parse_number<int>(name, args.value(), 1, 1000);
        } else if (name == "--seeds") {
            seeds = gc::cli::parse_list<std::uint64_t>(name, args.value(), [](auto opt, auto item) {
                return parse_number<std::uint64_t>(opt, item);
            });
        } else if (name == "--peer-particles") {
            peer_particles = parse_number<int>(name, args.value(), 1, 100000);
        } else {
            throw gc::cli::UsageError("unknown option " + std::string(name));
        }
    }
    if (quick) {
        o.particles = {50, 200};
        o.scenes = {gc::sim::Preset::Clean, gc::sim::Preset::Heavy};
        o.frames = 40;
        o.runs = 1;
        o.seeds = {1};
        o.peer_particles = 200;
    }
    // Explicit options win over --quick.
    if (particles) o.particles = *particles;
    if (scenes) o.scenes = *scenes;
    if (frames) o.frames = *frames;
    if (runs) o.runs = *runs;
    if (seeds) o.seeds = *seeds;
    if (peer_particles) o.peer_particles = *peer_particles;
    return o;
}

double ms_since(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v)
{
    if (v.empty())
        return std::nan("");
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    if (v.size() % 2 == 1)
        return *mid;
    return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

double box_iou(const cv::Rect& a, const cv::Rect& b)
{
    const double inter = (a & b).area();
    const double uni = static_cast<double>(a.area()) + b.area() - inter;
    return uni > 0.0 ? inter / uni : 0.0;
}

// One eye of one scene, rendered before anything is timed.
struct Sequence {
    std::vector<cv::Mat> frames;
    std::vector<cv::Mat1b> masks;
    std::vector<cv::Rect> boxes;
    std::vector<bool> visible;
    int first_visible = -1;
};

Sequence render_sequence(const gc::sim::Scene& scene, int frames, gc::Eye eye)
{
    Sequence s;
    s.frames.resize(frames);
    s.masks.resize(frames);
    s.boxes.resize(frames);
    s.visible.resize(frames);
    gc::sim::EyeTruth truth;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, eye, gc::HeadPose{}, s.frames[f], &truth);
        s.masks[f] = truth.mask.clone();
        s.boxes[f] = truth.bbox;
        s.visible[f] = truth.visible;
        if (truth.visible && s.first_visible < 0)
            s.first_visible = f;
    }
    return s;
}

// Accuracy of one particle count on one scene, pooled over seeds.
struct AccuracyRow {
    gc::SnrAccumulator snr;
    double iou_sum = 0.0;
    std::int64_t iou_frames = 0;
    std::int64_t tracked = 0;
    std::int64_t visible = 0;
    std::int64_t lost = 0;
    std::vector<double> ms;            // per seed: the median over runs
    std::vector<int> acquired_at;      // per seed: first tracking frame, -1 never
};

// Runs our tracker over a sequence `runs` times; the first run is also scored. Only
// HandTracker::process is timed. Returns the median over runs of the mean ms per frame.
// `boxes`, when given, receives our per-frame box (empty when not tracking) from the first run.
double run_tracker(const Sequence& seq, const gc::TrackerParams& params, int runs,
                   AccuracyRow* row, std::vector<cv::Rect>* boxes)
{
    const int n = static_cast<int>(seq.frames.size());
    const cv::Size size = seq.frames.front().size();
    const cv::Mat1b empty(size, 0);
    std::vector<double> per_run;
    for (int run = 0; run < runs; ++run) {
        gc::HandTracker tracker(params);
        double total_ms = 0.0;
        int acquired = -1;
        for (int f = 0; f < n; ++f) {
            const auto t0 = Clock::now();
            const gc::EyeEstimate& e = tracker.process(seq.frames[f]);
            total_ms += ms_since(t0);
            if (run != 0)
                continue;
            const bool tracking = e.state == gc::TrackState::Tracking;
            if (boxes)
                boxes->push_back(tracking && !e.contour.empty() ? cv::boundingRect(e.contour)
                                                                : cv::Rect());
            if (!row)
                continue;
            if (tracking && acquired < 0)
                acquired = f;
            if (seq.first_visible >= 0 && f >= seq.first_visible && seq.visible[f]) {
                ++row->visible;
                row->tracked += tracking ? 1 : 0;
            }
            if (acquired >= 0 && e.state == gc::TrackState::Lost)
                ++row->lost;
            // Scored from the first frame where the hand shows: the acquisition delay, like
            // any frame where we do not track, counts as an empty silhouette.
            if (seq.first_visible < 0 || f < seq.first_visible)
                continue;
            const cv::Mat1b tracked =
                tracking && !e.contour.empty() ? gc::contour_mask(e.contour, size) : empty;
            row->snr.add(seq.masks[f], tracked);
            row->iou_sum += gc::mask_iou(seq.masks[f], tracked);
            ++row->iou_frames;
        }
        if (run == 0 && row)
            row->acquired_at.push_back(acquired);
        per_run.push_back(total_ms / n);
    }
    return median(per_run);
}

// Box IoU and cost of one tracker over the frames after its initialisation frame.
struct PeerScore {
    double iou_sum = 0.0;
    std::int64_t frames = 0;
    std::vector<double> ms;
};

void score_boxes(const Sequence& seq, int from, const std::vector<std::optional<cv::Rect>>& boxes,
                 PeerScore& score)
{
    for (int f = from; f < static_cast<int>(seq.frames.size()); ++f) {
        if (!seq.visible[f])
            continue;
        score.iou_sum += boxes[f] ? box_iou(*boxes[f], seq.boxes[f]) : 0.0;
        ++score.frames;
    }
}

// Baseline: the cost of touching the frame once (a copy and a BGR -> RGB conversion).
struct Baseline {
    double copy_ms = 0.0;
    double convert_ms = 0.0;
};

Baseline measure_baseline(const Sequence& seq, int runs)
{
    cv::Mat copy, converted;
    std::vector<double> copy_runs, convert_runs;
    const double n = static_cast<double>(seq.frames.size());
    for (int run = 0; run < std::max(runs, 5); ++run) {
        auto t0 = Clock::now();
        for (const cv::Mat& f : seq.frames)
            f.copyTo(copy);
        copy_runs.push_back(ms_since(t0) / n);
        t0 = Clock::now();
        for (const cv::Mat& f : seq.frames)
            cv::cvtColor(f, converted, cv::COLOR_BGR2RGB);
        convert_runs.push_back(ms_since(t0) / n);
    }
    return {median(copy_runs), median(convert_runs)};
}

double angle_deg(const cv::Vec3d& a, const cv::Vec3d& b)
{
    const double c = a.dot(b) / (cv::norm(a) * cv::norm(b));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// The 3D step on the clean stereo scene: its cost per stereo frame and its accuracy against
// the scene's ground truth (head frame), and the whole stereo pipeline's throughput.
struct StereoFigures {
    int frames = 0;
    int valid = 0;
    double estimate_ms = std::nan("");
    double direction_error_deg = std::nan("");
    double palm_error_mm = std::nan("");
    double fps = std::nan("");
};

StereoFigures measure_stereo(const Options& o)
{
    gc::sim::SceneConfig config;
    config.preset = gc::sim::Preset::Clean;
    config.motion = o.motion;
    config.seed = o.seeds.front();
    const gc::sim::Scene scene(config);
    const Sequence left = render_sequence(scene, o.frames, gc::Eye::Left);
    const Sequence right = render_sequence(scene, o.frames, gc::Eye::Right);
    gc::TrackerParams params;
    params.particles = o.peer_particles;
    params.seed = config.seed;

    StereoFigures out;
    out.frames = o.frames;
    {
        gc::StereoHandTracker trackers(params);
        gc::PointingEstimator estimator(scene.calibration());
        std::vector<double> ms, direction_err, palm_err;
        for (int f = 0; f < o.frames; ++f) {
            const gc::StereoEstimate e = trackers.process(left.frames[f], right.frames[f]);
            if (!e.left.valid() || !e.right.valid())
                continue;
            const auto t0 = Clock::now();
            const gc::Pointing3D p = estimator.estimate(left.frames[f], right.frames[f], e.left, e.right);
            ms.push_back(ms_since(t0));
            if (!p.valid)
                continue;
            ++out.valid;
            const gc::sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
            direction_err.push_back(angle_deg(p.direction_head, truth.direction));
            palm_err.push_back(cv::norm(p.palm_head_mm - truth.palm_mm));
        }
        out.estimate_ms = median(ms);
        out.direction_error_deg = median(direction_err);
        out.palm_error_mm = median(palm_err);
    }
    std::vector<double> fps_runs;
    for (int run = 0; run < o.runs; ++run) {
        gc::PointingTracker pipeline(params, scene.calibration());
        const auto t0 = Clock::now();
        for (int f = 0; f < o.frames; ++f)
            pipeline.process_stereo(left.frames[f], right.frames[f]);
        fps_runs.push_back(1000.0 * o.frames / ms_since(t0));
    }
    out.fps = median(fps_runs);
    return out;
}

std::string fixed(double v, int decimals)
{
    if (!std::isfinite(v))
        return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

double mean(const std::vector<double>& v)
{
    if (v.empty())
        return std::nan("");
    double s = 0.0;
    for (double x : v)
        s += x;
    return s / static_cast<double>(v.size());
}

struct PeerRow {
    std::string scene;
    std::string tracker;
    double iou = 0.0;
    double ms = 0.0;
    std::int64_t frames = 0;
};

int run_bench(const Options& o)
{
    cv::setNumThreads(1);  // per-eye figures are single-threaded
    const gc::tools::MachineInfo machine = gc::tools::machine_info();
    std::string seeds_text;
    for (std::uint64_t s : o.seeds) {
        if (!seeds_text.empty())
            seeds_text += ',';
        seeds_text += std::to_string(s);
    }

    std::map<std::pair<int, int>, AccuracyRow> rows;  // (scene index, particles)
    std::vector<std::vector<double>> skin_fraction(o.scenes.size());
    std::vector<PeerRow> peer_rows;
    std::vector<Baseline> baselines;

    for (std::size_t si = 0; si < o.scenes.size(); ++si) {
        const std::string scene_name(gc::sim::to_string(o.scenes[si]));
        std::map<std::string, PeerScore> peer_scores;
        for (std::uint64_t seed : o.seeds) {
            gc::sim::SceneConfig config;
            config.preset = o.scenes[si];
            config.motion = o.motion;
            config.seed = seed;
            const gc::sim::Scene scene(config);
            std::cerr << "gesturecam-bench: " << scene_name << ", seed " << seed << '\n';
            const Sequence seq = render_sequence(scene, o.frames, gc::Eye::Left);
            skin_fraction[si].push_back(scene.measured_skin_fraction(0));
            baselines.push_back(measure_baseline(seq, o.runs));

            for (int particles : o.particles) {
                gc::TrackerParams params;
                params.particles = particles;
                params.seed = seed;
                AccuracyRow& row = rows[{static_cast<int>(si), particles}];
                row.ms.push_back(run_tracker(seq, params, o.runs, &row, nullptr));
            }
            if (!o.peers)
                continue;

            // Peers start from the true box at the frame where we acquire (or where the hand
            // first shows, if we never do) and are scored on the same frames after it.
            gc::TrackerParams params;
            params.particles = o.peer_particles;
            params.seed = seed;
            std::vector<cv::Rect> our_boxes;
            AccuracyRow ours_row;
            const double our_ms = run_tracker(seq, params, 1, &ours_row, &our_boxes);
            int init = ours_row.acquired_at.front() >= 0 ? ours_row.acquired_at.front() : seq.first_visible;
            while (init >= 0 && init < o.frames && !seq.visible[init])
                ++init;
            if (init < 0 || init >= o.frames - 1)
                continue;  // the hand never shows: nothing to compare
            std::vector<std::optional<cv::Rect>> boxes(o.frames);
            for (int f = 0; f < o.frames; ++f)
                if (our_boxes[f].area() > 0)
                    boxes[f] = our_boxes[f];
            PeerScore& ours = peer_scores["gesturecam"];
            score_boxes(seq, init + 1, boxes, ours);
            ours.ms.push_back(our_ms);
            for (auto& peer : gc::tools::make_peer_trackers()) {
                std::fill(boxes.begin(), boxes.end(), std::nullopt);
                try {
                    peer->init(seq.frames[init], seq.boxes[init], seq.masks[init]);
                } catch (const std::exception& e) {
                    // Scored as never finding the hand, so the tables stay comparable.
                    std::cerr << "gesturecam-bench: warning: " << peer->name() << " could not start on "
                              << scene_name << " seed " << seed << ": " << e.what() << '\n';
                    score_boxes(seq, init + 1, boxes, peer_scores[std::string(peer->name())]);
                    continue;
                }
                double total = 0.0;
                for (int f = init + 1; f < o.frames; ++f) {
                    const auto t0 = Clock::now();
                    boxes[f] = peer->update(seq.frames[f]);
                    total += ms_since(t0);
                }
                PeerScore& score = peer_scores[std::string(peer->name())];
                score_boxes(seq, init + 1, boxes, score);
                score.ms.push_back(total / (o.frames - init - 1));
            }
        }
        for (const auto& [name, score] : peer_scores)
            peer_rows.push_back({scene_name, name,
                                 score.frames > 0 ? score.iou_sum / score.frames : std::nan(""),
                                 mean(score.ms), score.frames});
        // Ours first, then OpenCV's in a fixed order.
        std::stable_partition(peer_rows.end() - static_cast<std::ptrdiff_t>(peer_scores.size()),
                              peer_rows.end(), [](const PeerRow& r) { return r.tracker == "gesturecam"; });
    }

    std::cerr << "gesturecam-bench: stereo\n";
    const StereoFigures stereo = measure_stereo(o);
    std::vector<double> copy_ms, convert_ms;
    for (const Baseline& b : baselines) {
        copy_ms.push_back(b.copy_ms);
        convert_ms.push_back(b.convert_ms);
    }
    const Baseline baseline{median(copy_ms), median(convert_ms)};

    using gc::tools::JsonObject;
    if (o.json) {
        std::cout << JsonObject()
                         .add("kind", "machine")
                         .add("cores", static_cast<int>(machine.cores))
                         .add("cpu", machine.cpu_model)
                         .add("load_1min", machine.load_1min, 2)
                         .add("opencv", CV_VERSION)
                         .add("width", 640)
                         .add("height", 480)
                         .add("frames", o.frames)
                         .add("runs", o.runs)
                         .add("seeds", seeds_text)
                         .add("motion", gc::sim::to_string(o.motion))
                         .str()
                  << '\n';
        std::cout << JsonObject()
                         .add("kind", "baseline")
                         .add("copy_ms", baseline.copy_ms, 4)
                         .add("convert_ms", baseline.convert_ms, 4)
                         .str()
                  << '\n';
    } else {
        std::cout << "# gesturecam-bench\n\n"
                  << "machine: " << machine.cores << " cores, " << machine.cpu_model
                  << ", load average " << fixed(machine.load_1min, 2) << " at start\n"
                  << "OpenCV " << CV_VERSION << ", one OpenCV thread; 640x480, " << o.frames
                  << " frames per sequence, motion " << gc::sim::to_string(o.motion)
                  << ", seeds " << seeds_text << ", median of " << o.runs << " run(s)\n"
                  << "baseline per frame: copy " << fixed(baseline.copy_ms, 3)
                  << " ms, BGR->RGB conversion " << fixed(baseline.convert_ms, 3) << " ms\n\n"
                  << "## Accuracy and cost by particle count (thesis Tables 4.1, 4.2)\n\n"
                  << "| scene | skin % | particles | SNR dB | mean IoU | tracked | lost frames | "
                     "ms/frame/eye | x conversion |\n"
                  << "|---|---|---|---|---|---|---|---|---|\n";
    }
    for (std::size_t si = 0; si < o.scenes.size(); ++si) {
        const std::string_view scene_name = gc::sim::to_string(o.scenes[si]);
        const double skin_pct = 100.0 * mean(skin_fraction[si]);
        for (int particles : o.particles) {
            const AccuracyRow& r = rows.at({static_cast<int>(si), particles});
            const double iou = r.iou_frames > 0 ? r.iou_sum / r.iou_frames : std::nan("");
            const double tracked = r.visible > 0 ? static_cast<double>(r.tracked) / r.visible : 0.0;
            const double lost = static_cast<double>(r.lost) / o.seeds.size();
            const double ms = mean(r.ms);
            if (o.json) {
                std::cout << JsonObject()
                                 .add("kind", "tracker")
                                 .add("scene", scene_name)
                                 .add("skin_pct", skin_pct, 2)
                                 .add("particles", particles)
                                 .add("snr_db", r.snr.snr_db(), 2)
                                 .add("mean_iou", iou, 3)
                                 .add("tracked_fraction", tracked, 3)
                                 .add("lost_frames", lost, 1)
                                 .add("ms_per_frame", ms, 3)
                                 .str()
                          << '\n';
            } else {
                std::cout << "| " << scene_name << " | " << fixed(skin_pct, 2) << " | " << particles
                          << " | " << fixed(r.snr.snr_db(), 2) << " | " << fixed(iou, 3) << " | "
                          << fixed(tracked, 3) << " | " << fixed(lost, 1) << " | " << fixed(ms, 2)
                          << " | " << fixed(ms / baseline.convert_ms, 1) << " |\n";
            }
        }
    }
    if (!o.json && !peer_rows.empty())
        std::cout << "\n## OpenCV trackers on the same frames (box IoU vs the true box; ours at "
                  << o.peer_particles << " particles)\n\n"
                  << "| scene | tracker | box IoU | ms/frame | frames scored |\n|---|---|---|---|---|\n";
    for (const PeerRow& p : peer_rows) {
        if (o.json)
            std::cout << JsonObject()
                             .add("kind", "peer")
                             .add("scene", p.scene)
                             .add("tracker", p.tracker)
                             .add("particles", o.peer_particles)
                             .add("box_iou", p.iou, 3)
                             .add("ms_per_frame", p.ms, 3)
                             .add("frames", p.frames)
                             .str()
                      << '\n';
        else
            std::cout << "| " << p.scene << " | " << p.tracker << " | " << fixed(p.iou, 3) << " | "
                      << fixed(p.ms, 2) << " | " << p.frames << " |\n";
    }
    if (o.json) {
        std::cout << JsonObject()
                         .add("kind", "stereo")
                         .add("scene", "clean")
                         .add("particles", o.peer_particles)
                         .add("frames", stereo.frames)
                         .add("valid_3d", stereo.valid)
                         .add("estimate_ms", stereo.estimate_ms, 3)
                         .add("direction_error_deg", stereo.direction_error_deg, 2)
                         .add("palm_error_mm", stereo.palm_error_mm, 1)
                         .add("pipeline_fps", stereo.fps, 2)
                         .add("threads", 2)
                         .str()
                  << '\n';
    } else {
        std::cout << "\n## Stereo (clean scene, " << o.peer_particles << " particles per eye)\n\n"
                  << "| 3D step ms/stereo frame | 3D valid frames | median direction error deg | "
                     "median palm error mm | pipeline frames/s (2 threads) |\n"
                  << "|---|---|---|---|---|\n"
                  << "| " << fixed(stereo.estimate_ms, 2) << " | " << stereo.valid << "/"
                  << stereo.frames << " | " << fixed(stereo.direction_error_deg, 1) << " | "
                  << fixed(stereo.palm_error_mm, 0) << " | " << fixed(stereo.fps, 1) << " |\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    Options options;
    try {
        options = parse_options(argc, argv);
    } catch (const gc::cli::UsageError& e) {
        std::cerr << "gesturecam-bench: " << e.what() << "\n\n" << kUsage;
        return 2;
    }
    if (options.help) {
        std::cout << kUsage;
        return 0;
    }
    try {
        return run_bench(options);
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-bench: error: " << e.what() << '\n';
        return 1;
    }
}
