#include "tools/stereo_runs.hpp"

#include "stereo/pointing.hpp"
#include "tools/bench_stats.hpp"
#include "tools/synthetic_runs.hpp"
#include "tracker/pointing_tracker.hpp"
#include "tracker/stereo_tracker.hpp"

#include <algorithm>
#include <numbers>

namespace gc::tools {

namespace {

double angle_deg(const cv::Vec3d& a, const cv::Vec3d& b)
{
    const double c = a.dot(b) / (cv::norm(a) * cv::norm(b));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

StereoFigures measure_stereo(const BenchOptions& o)
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
    std::vector<double> fps_runs;
    for (int run = 0; run < o.runs; ++run) {
        gc::PointingTracker pipeline(params, scene.calibration());
        const auto t0 = BenchClock::now();
        for (int f = 0; f < o.frames; ++f)
            pipeline.process_stereo(left.frames[f], right.frames[f]);
        fps_runs.push_back(1000.0 * o.frames / ms_since(t0));
    }
    out.fps = median(fps_runs);
    return out;
}

}  // namespace gc::tools
