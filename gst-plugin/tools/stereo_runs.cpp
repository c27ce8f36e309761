#include "tools/stereo_runs.hpp"

#include "stereo/pointing.hpp"
#include "tools/bench_stats.hpp"
#include "tools/synthetic_runs.hpp"
#include "tracker/pointing_tracker.hpp"
#include "tracker/stereo_tracker.hpp"

#include <array>

namespace gc::tools {

namespace {

struct Throughput {
    double fps = 0.0;     // stereo frames per second, wall time
    double cpu_ms = 0.0;  // CPU time per stereo frame, every thread of the process
};

// The whole pipeline over the scene, `runs` times; medians over runs. With `rendered`,
// on its frames rendered beforehand; without, both views are rendered in the timed loop
// on the calling thread, as a pair of scene sources feeding the tracker would do without
// running beside it. `models_share`, when given, receives the share of eye-frames of the
// first run on which the learned models ran.
Throughput throughput(const gc::TrackerParams& params, const gc::sim::Scene& scene, int frames, int runs,
                      const std::array<const Sequence*, 2>* rendered, double* models_share)
{
    std::vector<double> fps, cpu_ms;
    cv::Mat left, right;
    for (int run = 0; run < runs; ++run) {
        gc::PointingTracker pipeline(params, scene.calibration());
        int models = 0;
        const auto t0 = BenchClock::now();
        const double cpu0 = process_cpu_ms();
        for (int f = 0; f < frames; ++f) {
            if (rendered) {
                left = (*rendered)[0]->frames[f];
                right = (*rendered)[1]->frames[f];
            } else {
                scene.render(f, gc::Eye::Left, gc::HeadPose{}, left);
                scene.render(f, gc::Eye::Right, gc::HeadPose{}, right);
            }
            const gc::FrameResult& r = pipeline.process_stereo(left, right);
            models += int(r.left.models_ran) + int(r.right.models_ran);
        }
        cpu_ms.push_back((process_cpu_ms() - cpu0) / frames);
        fps.push_back(1000.0 * frames / ms_since(t0));
        if (run == 0 && models_share) *models_share = models / (2.0 * frames);
    }
    return {median(fps), median(cpu_ms)};
}

}  // namespace

StereoFigures measure_stereo(const BenchOptions& o, gc::HandDetector detector)
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
    params.detector = detector;

    StereoFigures out;
    out.detector = detector;
    out.frames = o.frames;
    {
        gc::StereoHandTracker trackers(params);
        gc::PointingEstimator estimator(scene.calibration());
        std::vector<double> ms, direction_err, palm_err;
        for (int f = 0; f < o.frames; ++f) {
            const gc::StereoEstimate e = trackers.process(left.frames[f], right.frames[f]);
            if (!e.left.valid() || !e.right.valid()) continue;
            const auto t0 = BenchClock::now();
            const gc::Pointing3D p = estimator.estimate(left.frames[f], right.frames[f], e.left, e.right);
            ms.push_back(ms_since(t0));
            if (!p.valid) continue;
            ++out.valid;
            const gc::sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
            direction_err.push_back(angle_deg(p.direction_head, truth.direction));
            palm_err.push_back(cv::norm(p.palm_head_mm - truth.palm_mm));
        }
        out.estimate_ms = median(ms);
        out.direction_error_deg = median(direction_err);
        out.palm_error_mm = median(palm_err);
    }
    const std::array<const Sequence*, 2> rendered{&left, &right};
    const Throughput tracking = throughput(params, scene, o.frames, o.runs, &rendered, &out.models_share);
    const Throughput whole = throughput(params, scene, o.frames, o.runs, nullptr, nullptr);
    out.fps = tracking.fps;
    out.cpu_ms = tracking.cpu_ms;
    out.rendering_fps = whole.fps;
    out.rendering_cpu_ms = whole.cpu_ms;
    return out;
}

}  // namespace gc::tools
