#include "tools/stereo_runs.hpp"

#include "stereo/pointing.hpp"
#include "tools/bench_stats.hpp"
#include "tools/synthetic_runs.hpp"
#include "tracker/pointing_tracker.hpp"
#include "tracker/stereo_tracker.hpp"


namespace gc::tools {

namespace {

// Stereo frames per second of the whole pipeline on frames rendered beforehand, one
// figure per run; `models_share` receives the share of eye-frames of the first run on
// which the learned models ran.
std::vector<double> tracker_fps(const gc::TrackerParams& params, const gc::sim::Scene& scene,
                                const Sequence& left, const Sequence& right, int runs,
                                double* models_share)
{
    const int frames = static_cast<int>(left.frames.size());
    std::vector<double> fps;
    for (int run = 0; run < runs; ++run) {
        gc::PointingTracker pipeline(params, scene.calibration());
        int models = 0;
        const auto t0 = BenchClock::now();
        for (int f = 0; f < frames; ++f) {
            const gc::FrameResult& r = pipeline.process_stereo(left.frames[f], right.frames[f]);
            models += int(r.left.models_ran) + int(r.right.models_ran);
        }
        fps.push_back(1000.0 * frames / ms_since(t0));
        if (run == 0)
            *models_share = models / (2.0 * frames);
    }
    return fps;
}

// The same with both eyes rendered in the timed loop, on the calling thread, as a pair of
// scene sources feeding the tracker would do without running beside it.
std::vector<double> rendering_fps(const gc::TrackerParams& params, const gc::sim::Scene& scene,
                                  int frames, int runs)
{
    std::vector<double> fps;
    cv::Mat left, right;
    for (int run = 0; run < runs; ++run) {
        gc::PointingTracker pipeline(params, scene.calibration());
        const auto t0 = BenchClock::now();
        for (int f = 0; f < frames; ++f) {
            scene.render(f, gc::Eye::Left, gc::HeadPose{}, left);
            scene.render(f, gc::Eye::Right, gc::HeadPose{}, right);
            pipeline.process_stereo(left, right);
        }
        fps.push_back(1000.0 * frames / ms_since(t0));
    }
    return fps;
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
            if (!e.left.valid() || !e.right.valid())
                continue;
            const auto t0 = BenchClock::now();
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
    out.fps = median(tracker_fps(params, scene, left, right, o.runs, &out.models_share));
    out.rendering_fps = median(rendering_fps(params, scene, o.frames, o.runs));
    return out;
}

}  // namespace gc::tools
