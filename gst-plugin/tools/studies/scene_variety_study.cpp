// Not a test: figures of the scene variety (docs/sim.md).
//
//   scene_variety_study images PRESET VARIETY FIRST_SEED LAST_SEED FRAME DIR
//       writes DIR/<preset>-<variety>-<seed>.png: the left eye at FRAME, the hand's truth
//       outlined in green, the people's skin in blue, and DIR/<preset>-<variety>-sheet.png with
//       all of them at half size, four to a row
//   scene_variety_study cost PRESET VARIETY FIRST_SEED LAST_SEED
//       CPU time per rendered VGA eye (with truth), mean over 200 frames per seed
//   scene_variety_study clutter PRESET VARIETY FIRST_SEED LAST_SEED
//       per seed: the skin-pixel fraction of the background (Scene::measured_skin_fraction,
//       frame 0) and the hand's size (longest side of the mask) over 200 frames of the left eye
//   scene_variety_study track PRESET VARIETY FIRST_SEED LAST_SEED learned|motion [FRAMES [DIR]]
//       the default tracker (or the motion-only one) on the left eye of `mixed` sequences:
//       share of the frames with the hand in view that are tracked on the hand (mask IoU
//       >= 0.5 or fingertip within 20 px), median fingertip error of the tracked frames (and
//       of those on the hand), and the sequence's SNR (as tracking_study); with DIR, every
//       10th frame as DIR/track-<seed>-<frame>.png: the truth's outline and fingertip in
//       green, the tracked contour and fingertip in red
#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

namespace {

gc::sim::SceneConfig scene_config(gc::sim::Preset preset, gc::sim::Variety variety, int seed)
{
    gc::sim::SceneConfig cfg;
    cfg.preset = preset;
    cfg.variety = variety;
    cfg.motion = gc::sim::Motion::Mixed;
    cfg.seed = static_cast<std::uint64_t>(seed);
    return cfg;
}

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v)
{
    if (v.empty()) return NAN;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

int images(const gc::sim::SceneConfig& base, int first, int last, int frame, const std::string& dir)
{
    std::vector<cv::Mat> tiles;
    const std::string stem = dir + "/" + std::string(gc::sim::to_string(base.preset)) + "-" +
                             std::string(gc::sim::to_string(base.variety)) + "-";
    for (int seed = first; seed <= last; ++seed) {
        gc::sim::SceneConfig cfg = base;
        cfg.seed = static_cast<std::uint64_t>(seed);
        const gc::sim::Scene scene(cfg);
        cv::Mat bgr;
        gc::sim::EyeTruth truth;
        scene.render(frame, gc::Eye::Left, {}, bgr, &truth);
        std::vector<std::vector<cv::Point>> outline;
        cv::findContours(truth.mask.clone(), outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        cv::drawContours(bgr, outline, -1, cv::Scalar(0, 255, 0), 1);
        if (!truth.face.empty()) {
            cv::findContours(truth.face.clone(), outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
            cv::drawContours(bgr, outline, -1, cv::Scalar(255, 0, 0), 1);
        }
        cv::circle(bgr, truth.fingertip_px, 3, cv::Scalar(0, 0, 255), 1);
        cv::imwrite(stem + std::to_string(seed) + ".png", bgr);
        cv::Mat half;
        cv::resize(bgr, half, bgr.size() / 2, 0, 0, cv::INTER_AREA);
        tiles.push_back(half);
    }
    while (tiles.size() % 4) tiles.push_back(cv::Mat::zeros(tiles[0].size(), tiles[0].type()));
    std::vector<cv::Mat> rows;
    for (std::size_t i = 0; i < tiles.size(); i += 4) {
        cv::Mat row;
        cv::hconcat(std::vector<cv::Mat>(tiles.begin() + long(i), tiles.begin() + long(i) + 4), row);
        rows.push_back(row);
    }
    cv::Mat sheet;
    cv::vconcat(rows, sheet);
    cv::imwrite(stem + "sheet.png", sheet);
    return 0;
}

int cost(const gc::sim::SceneConfig& base, int first, int last)
{
    double total = 0.0, worst = 0.0;
    int frames = 0;
    for (int seed = first; seed <= last; ++seed) {
        gc::sim::SceneConfig cfg = base;
        cfg.seed = static_cast<std::uint64_t>(seed);
        const double t0 = cpu_seconds();
        const gc::sim::Scene scene(cfg);
        const double built = cpu_seconds() - t0;
        cv::Mat bgr;
        gc::sim::EyeTruth truth;
        const double t1 = cpu_seconds();
        for (int f = 0; f < 200; ++f) scene.render(f, gc::Eye(f % 2), {}, bgr, &truth);
        const double per_eye = (cpu_seconds() - t1) / 200.0;
        std::printf("seed %d build %.0f ms render %.2f ms per eye\n", seed, 1e3 * built, 1e3 * per_eye);
        total += per_eye * 200.0;
        frames += 200;
        worst = std::max(worst, per_eye);
    }
    std::printf("mean %.2f ms per eye, worst seed %.2f ms\n", 1e3 * total / frames, 1e3 * worst);
    return 0;
}

int clutter(const gc::sim::SceneConfig& base, int first, int last)
{
    std::vector<double> fractions, sides;
    for (int seed = first; seed <= last; ++seed) {
        gc::sim::SceneConfig cfg = base;
        cfg.seed = static_cast<std::uint64_t>(seed);
        const gc::sim::Scene scene(cfg);
        const double fraction = scene.measured_skin_fraction();
        std::vector<double> seed_sides;
        cv::Mat bgr;
        gc::sim::EyeTruth truth;
        for (int f = 0; f < 200; f += 5) {
            scene.render(f, gc::Eye::Left, {}, bgr, &truth);
            if (truth.visible) seed_sides.push_back(std::max(truth.bbox.width, truth.bbox.height));
        }
        std::printf("seed %d skin fraction %.2f %% hand %.0f px\n", seed, 100.0 * fraction, median(seed_sides));
        fractions.push_back(fraction);
        sides.insert(sides.end(), seed_sides.begin(), seed_sides.end());
    }
    std::sort(fractions.begin(), fractions.end());
    std::sort(sides.begin(), sides.end());
    std::printf("skin fraction min %.2f %% median %.2f %% max %.2f %%; hand p10 %.0f median %.0f p90 %.0f px\n",
                100.0 * fractions.front(), 100.0 * median(fractions), 100.0 * fractions.back(),
                sides[sides.size() / 10], median(sides), sides[sides.size() * 9 / 10]);
    return 0;
}

// The frame with the truth's outline and fingertip in green, the tracked ones in red.
void write_overlay(const std::string& path, const cv::Mat& bgr, const gc::sim::EyeTruth& truth,
                   const gc::EyeEstimate& e, const cv::Mat1b& tracked)
{
    cv::Mat out = bgr.clone();
    std::vector<std::vector<cv::Point>> outlines;
    cv::findContours(truth.mask.clone(), outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(out, outlines, -1, cv::Scalar(0, 255, 0), 1);
    cv::circle(out, truth.fingertip_px, 4, cv::Scalar(0, 255, 0), 2);
    outlines.clear();
    cv::findContours(tracked.clone(), outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(out, outlines, -1, cv::Scalar(0, 0, 255), 1);
    if (e.valid()) cv::circle(out, cv::Point2d(e.fingertip), 4, cv::Scalar(0, 0, 255), 2);
    cv::imwrite(path, out);
}

int track(const gc::sim::SceneConfig& base, int first, int last, bool learned, int frames, const std::string& dir)
{
    std::vector<double> all_errors, all_on_errors;
    long on_hand_total = 0, in_view_total = 0;
    double snr_sum = 0.0;
    int seeds = 0;
    for (int seed = first; seed <= last; ++seed) {
        gc::sim::SceneConfig cfg = base;
        cfg.seed = static_cast<std::uint64_t>(seed);
        const gc::sim::Scene scene(cfg);
        gc::TrackerParams params;
        if (!learned) params.detector = gc::HandDetector::Motion;
        params.seed = cfg.seed;
        gc::HandTracker tracker(params);
        cv::Mat bgr;
        gc::sim::EyeTruth truth;
        gc::SnrAccumulator snr;
        std::vector<double> errors, on_errors;
        int on_hand = 0, in_view = 0;
        for (int f = 0; f < frames; ++f) {
            scene.render(f, gc::Eye::Left, {}, bgr, &truth);
            const gc::EyeEstimate& e = tracker.process(bgr);
            const cv::Mat1b tracked =
                e.valid() ? gc::contour_mask(e.contour, bgr.size()) : cv::Mat1b(bgr.size(), std::uint8_t{0});
            snr.add(truth.mask, tracked);
            if (!dir.empty() && f % 10 == 0)
                write_overlay(dir + "/track-" + std::to_string(seed) + "-" + std::to_string(f) + ".png", bgr, truth, e,
                              tracked);
            if (!truth.visible) continue;
            ++in_view;
            if (!e.valid()) continue;
            const double error = cv::norm(cv::Point2d(e.fingertip) - truth.fingertip_px);
            errors.push_back(error);
            if (gc::mask_iou(truth.mask, tracked) >= 0.5 || error <= 20.0) {
                ++on_hand;
                on_errors.push_back(error);
            }
        }
        std::printf("seed %d on hand %.1f %% (%d of %d) fingertip median %.1f px snr %.2f dB\n", seed,
                    in_view ? 100.0 * on_hand / in_view : 0.0, on_hand, in_view, median(errors), snr.snr_db());
        std::fflush(stdout);
        all_errors.insert(all_errors.end(), errors.begin(), errors.end());
        all_on_errors.insert(all_on_errors.end(), on_errors.begin(), on_errors.end());
        on_hand_total += on_hand;
        in_view_total += in_view;
        snr_sum += snr.snr_db();
        ++seeds;
    }
    std::printf("%s: on hand %.1f %% of %ld frames in view, fingertip median %.1f px over %zu tracked frames "
                "(%.1f px over those on the hand), mean snr %.2f dB over %d seeds\n",
                learned ? "learned" : "motion", 100.0 * on_hand_total / std::max(1L, in_view_total), in_view_total,
                median(all_errors), all_errors.size(), median(all_on_errors), snr_sum / seeds, seeds);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string mode = argc > 1 ? argv[1] : "";
    const auto preset = argc > 2 ? gc::sim::preset_from_string(argv[2]) : std::nullopt;
    const auto variety = argc > 3 ? gc::sim::variety_from_string(argv[3]) : std::nullopt;
    const int first = argc > 4 ? std::atoi(argv[4]) : -1, last = argc > 5 ? std::atoi(argv[5]) : -2;
    if (!preset || !variety || first < 0 || last < first) {
        std::fprintf(stderr, "usage: %s images|cost|clutter|track PRESET none|wide FIRST_SEED LAST_SEED ...\n",
                     argv[0]);
        return 2;
    }
    const gc::sim::SceneConfig base = scene_config(*preset, *variety, first);
    if (mode == "images" && argc == 8) return images(base, first, last, std::atoi(argv[6]), argv[7]);
    if (mode == "cost" && argc == 6) return cost(base, first, last);
    if (mode == "clutter" && argc == 6) return clutter(base, first, last);
    const std::string detector = argc > 6 ? argv[6] : "";
    if (mode == "track" && (detector == "learned" || detector == "motion"))
        return track(base, first, last, detector == "learned", argc > 7 ? std::atoi(argv[7]) : 200,
                     argc > 8 ? argv[8] : "");
    std::fprintf(stderr, "%s: bad arguments\n", argv[0]);
    return 2;
}
