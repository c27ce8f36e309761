// The 3D experiments of the thesis (4.4) repeated on the synthetic scene; prints the
// Markdown tables of docs/stereo.md.
//   stereo_study truth    placed hands, ground-truth per-eye estimates, exact calibration
//   stereo_study motor    the same with 0.5 degree of motor-angle error on every axis
//   stereo_study tracker  scripted scenes tracked end to end by the CONDENSATION trackers
//   stereo_study pointing PRESET VARIETY FIRST LAST [FRAMES]
//       the default pipeline (learned detector, 1000 particles) on the stereo `mixed`
//       sequences of seeds FIRST-LAST: per seed, the frames where the hand points and is in
//       both views, the share with a 3D ray, and the ray's angle to the truth (median, p90)
//   stereo_study held
//       framing_study director's six held hands, offline at the head's rest pose: the ray's
//       median angle over frames 30-89, and with the renderer's 2D fingertip and palm (the
//       outline's extreme point and centroid) put in for the tracked ones
#include "framing_episode.hpp"
#include "sim_pairs.hpp"

#include "sim/scene.hpp"
#include "stereo/head_geometry.hpp"
#include "stereo/pointing.hpp"
#include "tracker/pointing_tracker.hpp"
#include "tracker/stereo_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace {

using gc::test::percentile;

struct Sample {
    double true_depth, est_depth;  // fingertip, head frame z
    double true_az, est_az, true_el, est_el;
    double angle_error;
};

double mean(const std::vector<double>& v)
{
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? NAN : s / v.size();
}

double stddev(const std::vector<double>& v)
{
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return v.size() < 2 ? 0.0 : std::sqrt(s / (v.size() - 1));
}

double slope(const std::vector<Sample>& s)
{
    double mx = 0, my = 0;
    for (const auto& x : s) mx += x.true_depth, my += x.est_depth;
    mx /= s.size(), my /= s.size();
    double sxy = 0, sxx = 0;
    for (const auto& x : s)
        sxy += (x.true_depth - mx) * (x.est_depth - my), sxx += (x.true_depth - mx) * (x.true_depth - mx);
    return sxy / sxx;
}

void summary(const std::vector<Sample>& s, int invalid, int total)
{
    std::vector<double> angle, depth;
    for (const auto& x : s) angle.push_back(x.angle_error), depth.push_back(std::abs(x.est_depth - x.true_depth));
    std::printf(
        "\n| pairs | valid | angle error median | p90 | max | fingertip depth error median | p90 | slope |\n"
        "|---|---|---|---|---|---|---|---|\n| %d | %d | %.2f deg | %.2f deg | %.2f deg | %.1f mm | %.1f mm | %.4f |\n",
        total, total - invalid, percentile(angle, 0.5), percentile(angle, 0.9), percentile(angle, 1.0),
        percentile(depth, 0.5), percentile(depth, 0.9), slope(s));
}

using SamplesBy = std::map<double, std::vector<Sample>>;

void print_by_depth(const SamplesBy& by_depth)
{
    std::printf("\nDepth (palm placed at the given distance; fingertip depth, mean +/- sd over poses and hands)\n\n"
                "| palm depth | true fingertip depth | estimated | error mean | error sd |\n|---|---|---|---|---|\n");
    for (const auto& [z, s] : by_depth) {
        std::vector<double> t, e, d;
        for (const auto& x : s)
            t.push_back(x.true_depth), e.push_back(x.est_depth), d.push_back(x.est_depth - x.true_depth);
        std::printf("| %.0f mm | %.1f mm | %.1f mm | %+.1f mm | %.1f mm |\n", z, mean(t), mean(e), mean(d), stddev(d));
    }
}

void print_by_yaw(const SamplesBy& by_yaw)
{
    std::printf("\nHorizontal angle (azimuth of the pointing direction) by yaw of the hand plane, finger "
                "horizontal (roll 0 and 180)\n\n| yaw | roll | true azimuth | estimated (mean) | sd | max error |\n"
                "|---|---|---|---|---|---|\n");
    for (const auto& [yaw, s] : by_yaw)
        for (double roll : {0.0, 180.0}) {
            std::vector<double> e, err;
            double truth = 0.0;
            for (const auto& x : s) {
                // Horizontal pointing (roll 0 or 180): zero elevation; the sign of the
                // azimuth tells the two apart.
                if (std::abs(x.true_el) > 1e-6) continue;
                const bool rightwards = x.true_az > 0.0;
                if (rightwards != (roll == 0.0)) continue;
                truth = x.true_az;
                e.push_back(x.est_az);
                err.push_back(std::abs(x.est_az - x.true_az));
            }
            if (e.empty()) continue;
            std::printf("| %+.1f | %.0f | %.1f deg | %.1f deg | %.2f deg | %.2f deg |\n", yaw, roll, truth, mean(e),
                        stddev(e), percentile(err, 1.0));
        }
}

void print_by_roll(const SamplesBy& by_roll)
{
    std::printf(
        "\nVertical angle (elevation) by roll of the finger in the hand plane\n\n"
        "| roll | true elevation (range over yaws) | error mean | error sd | max error |\n|---|---|---|---|---|\n");
    for (const auto& [roll, s] : by_roll) {
        std::vector<double> err, t;
        for (const auto& x : s) err.push_back(x.est_el - x.true_el), t.push_back(x.true_el);
        std::printf("| %+.0f | %.1f .. %.1f deg | %+.2f deg | %.2f deg | %.2f deg |\n", roll, percentile(t, 0.0),
                    percentile(t, 1.0), mean(err), stddev(err),
                    std::max(std::abs(percentile(err, 0.0)), percentile(err, 1.0)));
    }
}

void placed_hands(double motor_error_deg)
{
    const std::vector<double> depths{860, 1060, 1250}, yaws{-45, -22.5, 0, 22.5, 45};
    const std::vector<double> rolls{-60, -30, 0, 30, 60, 120, 150, 180};
    const gc::HeadPose nominal = motor_error_deg > 0 ? gc::HeadPose{4.0, -3.0, 3.0, -3.0} : gc::HeadPose{};
    std::vector<Sample> samples;
    SamplesBy by_depth, by_yaw, by_roll;
    int invalid = 0, total = 0, k = 0;
    std::vector<double> ms;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        gc::sim::SceneConfig config;
        config.preset = gc::sim::Preset::Light;
        config.motion = gc::sim::Motion::Static;
        config.seed = seed;
        const gc::sim::Scene scene(config);
        gc::PointingEstimator estimator(scene.calibration());
        cv::Mat left, right;
        for (double z : depths)
            for (double yaw : yaws)
                for (double roll : rolls) {
                    gc::sim::HandPose hand;
                    // Positions spread over the view: the rendering's sub-pixel phase varies too.
                    hand.palm_mm = {-60.0 + 23.0 * ((k + 1) % 5 - 2), 40.0 + 17.0 * ((k + 1) % 3 - 1), z};
                    hand.yaw_deg = yaw;
                    hand.roll_deg = roll;
                    gc::HeadPose render = nominal;
                    ++k;
                    render.pan_deg += (k & 1 ? 1 : -1) * motor_error_deg;
                    render.tilt_deg += (k & 2 ? 1 : -1) * motor_error_deg;
                    render.verge_left_deg += (k & 4 ? 1 : -1) * motor_error_deg;
                    render.verge_right_deg += (k % 3 ? 1 : -1) * motor_error_deg;
                    const auto t0 = std::chrono::steady_clock::now();
                    const auto r = gc::test::run_pose(scene, estimator, hand, render, nominal, k, left, right);
                    if (!r.visible) continue;
                    ++total;
                    if (!r.estimate.valid) {
                        ++invalid;
                        continue;
                    }
                    ms.push_back(
                        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                    Sample s;
                    s.true_depth = r.truth.fingertip_mm[2];
                    s.est_depth = r.estimate.fingertip_head_mm[2];
                    gc::direction_angles(r.truth.direction, s.true_az, s.true_el);
                    s.est_az = r.estimate.azimuth_head_deg;
                    s.est_el = r.estimate.elevation_head_deg;
                    s.angle_error = r.angle_error_deg;
                    samples.push_back(s);
                    by_depth[z].push_back(s);
                    by_yaw[yaw].push_back(s);
                    by_roll[roll].push_back(s);
                }
    }
    summary(samples, invalid, total);

    print_by_depth(by_depth);
    print_by_yaw(by_yaw);
    print_by_roll(by_roll);
    std::printf("\nRender + estimate per pose: median %.2f ms\n", percentile(ms, 0.5));
}

void tracked_scenes()
{
    std::printf("\n| scene | motion | frames with both eyes tracking | valid rays | angle error median | p90 | "
                "fingertip depth error median |\n|---|---|---|---|---|---|---|\n");
    std::vector<double> all_angle;
    for (const auto& [preset, motion] : std::vector<std::pair<gc::sim::Preset, gc::sim::Motion>>{
             {gc::sim::Preset::Clean, gc::sim::Motion::Static},
             {gc::sim::Preset::Clean, gc::sim::Motion::Yaw},
             {gc::sim::Preset::Light, gc::sim::Motion::Mixed},
         }) {
        gc::sim::SceneConfig config;
        config.preset = preset;
        config.motion = motion;
        config.seed = 5;
        const gc::sim::Scene scene(config);
        const int frames = 240;
        const auto [tracking, angle, depth] = gc::test::track_scene(scene, 500, frames);
        all_angle.insert(all_angle.end(), angle.begin(), angle.end());
        std::printf("| %s | %s | %d / %d | %zu | %.1f deg | %.1f deg | %.0f mm |\n",
                    std::string(gc::sim::to_string(preset)).c_str(), std::string(gc::sim::to_string(motion)).c_str(),
                    tracking, frames, angle.size(), percentile(angle, 0.5), percentile(angle, 0.9),
                    percentile(depth, 0.5));
        std::fflush(stdout);
    }
    std::printf("\nAll tracked frames: angle error median %.1f deg, p90 %.1f deg (n=%zu)\n", percentile(all_angle, 0.5),
                percentile(all_angle, 0.9), all_angle.size());
}

// One seed's stereo sequence through the default pipeline: the angle of each ray reported on
// a frame where the rendered hand points and is in both views; `pointing` counts those frames.
std::vector<double> pointing_angles(const gc::sim::SceneConfig& config, int frames, int& pointing)
{
    const gc::sim::Scene scene(config);
    gc::TrackerParams params;
    params.seed = config.seed;
    gc::PointingTracker pipeline(params, scene.calibration());
    cv::Mat left, right;
    gc::sim::EyeTruth left_truth, right_truth;
    std::vector<double> angles;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, gc::Eye::Left, {}, left, &left_truth);
        scene.render(f, gc::Eye::Right, {}, right, &right_truth);
        const gc::FrameResult& r = pipeline.process_stereo(left, right);
        const gc::sim::HandTruth truth = scene.hand_truth(scene.hand_pose(f));
        if (!truth.points() || !left_truth.visible || !right_truth.visible) continue;
        ++pointing;
        if (r.pointing.valid) angles.push_back(gc::test::angle_between_deg(r.pointing.direction_head, truth.direction));
    }
    return angles;
}

int pointing_rays(int argc, char** argv)
{
    if (argc < 6) {
        std::fprintf(stderr, "usage: stereo_study pointing PRESET none|wide FIRST LAST [FRAMES]\n");
        return 2;
    }
    gc::sim::SceneConfig config;
    config.preset = gc::sim::preset_from_string(argv[2]).value_or(gc::sim::Preset::Clean);
    config.variety = gc::sim::variety_from_string(argv[3]).value_or(gc::sim::Variety::None);
    config.motion = gc::sim::Motion::Mixed;
    const int first = std::atoi(argv[4]), last = std::atoi(argv[5]);
    const int frames = argc > 6 ? std::atoi(argv[6]) : 200;
    std::vector<double> all;
    int all_pointing = 0;
    for (int seed = first; seed <= last; ++seed) {
        config.seed = std::uint64_t(seed);
        int pointing = 0;
        const std::vector<double> angles = pointing_angles(config, frames, pointing);
        std::printf("seed %d: %zu rays on %d pointing frames, angle median %.1f deg, p90 %.1f deg\n", seed,
                    angles.size(), pointing, percentile(angles, 0.5), percentile(angles, 0.9));
        std::fflush(stdout);
        all.insert(all.end(), angles.begin(), angles.end());
        all_pointing += pointing;
    }
    std::printf("all: %zu rays on %d pointing frames (%.1f %%), angle median %.1f deg, p90 %.1f deg\n", all.size(),
                all_pointing, 100.0 * all.size() / std::max(1, all_pointing), percentile(all, 0.5),
                percentile(all, 0.9));
    return 0;
}

}  // namespace

// A held hand's rays, and the same frames' rays with the renderer's 2D points in place of
// the tracked ones: both, the fingertip only, the palm only.
struct HeldRays {
    std::vector<double> tracked, true_points, true_tip, true_palm;
};

// The angle to `truth` of the ray the 3D step gives with the tracked estimates, the renderer's
// fingertip and palm put in where asked; nothing when it gives no ray.
std::optional<double> ray_with(gc::PointingEstimator& step, const cv::Mat& left, const cv::Mat& right,
                               const gc::FrameResult& r, const gc::sim::EyeTruth (&eye)[2], bool true_tip,
                               bool true_palm, const cv::Vec3d& truth)
{
    gc::EyeEstimate e[2] = {r.left, r.right};
    for (int i = 0; i < 2; ++i) {
        if (true_tip) e[i].fingertip = cv::Point2f(eye[i].fingertip_px);
        if (true_palm) e[i].palm = cv::Point2f(eye[i].palm_px);
    }
    const gc::Pointing3D p = step.estimate(left, right, e[0], e[1]);
    if (!p.valid) return std::nullopt;
    return gc::test::angle_between_deg(p.direction_head, truth);
}

// One held hand of framing_study director (light scene, static, head at rest), frames 30-89.
HeldRays held_rays(int seed)
{
    gc::sim::SceneConfig c;
    c.preset = gc::sim::Preset::Light;
    c.motion = gc::sim::Motion::Static;
    c.seed = static_cast<std::uint64_t>(seed);
    const cv::Vec3d palm = gc::sim::Scene(c).hand_pose(60).palm_mm;
    const auto& d = gc::study::kSideDirections[std::size_t(seed - 1) % std::size(gc::study::kSideDirections)];
    // Any point along the direction aims the hand alike.
    c.aim_mm = palm + 2000.0 * (gc::rotation_about_y(d[0]) * gc::rotation_about_x(d[1]) * cv::Vec3d(0, 0, 1));
    const gc::sim::Scene scene(c);
    gc::TrackerParams params;
    params.seed = c.seed;
    gc::PointingTracker pipeline(params, scene.calibration());
    gc::PointingEstimator step(scene.calibration());
    cv::Mat left, right;
    gc::sim::EyeTruth eye[2];
    HeldRays rays;
    for (int f = 0; f < 90; ++f) {
        scene.render(f, gc::Eye::Left, {}, left, &eye[0]);
        scene.render(f, gc::Eye::Right, {}, right, &eye[1]);
        const gc::FrameResult r = pipeline.process_stereo(left, right);
        if (f < 30 || !r.pointing.valid) continue;
        const cv::Vec3d truth = scene.hand_truth(scene.hand_pose(f)).direction;
        rays.tracked.push_back(gc::test::angle_between_deg(r.pointing.direction_head, truth));
        const auto add = [](std::vector<double>& to, std::optional<double> angle) {
            if (angle) to.push_back(*angle);
        };
        add(rays.true_points, ray_with(step, left, right, r, eye, true, true, truth));
        add(rays.true_tip, ray_with(step, left, right, r, eye, true, false, truth));
        add(rays.true_palm, ray_with(step, left, right, r, eye, false, true, truth));
    }
    return rays;
}

// The director study's held hands offline: where each seed's ray error comes from.
void held_hands()
{
    std::printf("| seed, finger (right, up) | rays of 60 | median angle | with the true fingertip and palm | "
                "fingertip only | palm only |\n|---|---|---|---|---|---|\n");
    for (int seed = 1; seed <= 6; ++seed) {
        const HeldRays r = held_rays(seed);
        const auto& d = gc::study::kSideDirections[std::size_t(seed - 1)];
        std::printf("| %d (%+.0f, %+.0f) | %zu | %.1f deg | %.1f deg | %.1f deg | %.1f deg |\n", seed, d[0], d[1],
                    r.tracked.size(), percentile(r.tracked, 0.5), percentile(r.true_points, 0.5),
                    percentile(r.true_tip, 0.5), percentile(r.true_palm, 0.5));
    }
}

int main(int argc, char** argv)
{
    const std::string mode = argc > 1 ? argv[1] : "truth";
    try {
        if (mode == "truth")
            placed_hands(0.0);
        else if (mode == "motor")
            placed_hands(0.5);
        else if (mode == "tracker")
            tracked_scenes();
        else if (mode == "held")
            held_hands();
        else if (mode == "pointing")
            return pointing_rays(argc, argv);
        else {
            std::fprintf(stderr, "usage: stereo_study truth|motor|tracker|pointing|held\n");
            return 2;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "stereo_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
