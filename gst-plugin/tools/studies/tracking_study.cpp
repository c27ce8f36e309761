// Not a test: the per-seed figures behind the tables of docs/adr/. For each scene seed it
// tracks one eye (the left unless told) of a 200-frame `mixed` sequence and prints the
// sequence's SNR and, for face-pass, the frames where the hand covers at least 5 % of the
// face's skin and, of those, the ones where the tracker was lost or off the hand
// (IoU < 0.5), as in HandTracker.KeepsTheHandWhileItCrossesAFace. Of the frames off the hand,
// `lost` were reported lost (the rest tracked something else), and `entry` is the IoU on the
// first crossing frame: low when the tracker was already wrong before the face.
//
//   tracking_study PRESET FIRST_SEED LAST_SEED [PARTICLES [left|right [trace] [learned] [jpeg=Q]]]
//
// `trace` also prints one line per frame: state, confidence, IoU with the hand, scale, and
// whether the hand crosses the face. `learned` tracks with the palm and landmark models
// instead of the thesis's motion detector. `jpeg=Q` passes every frame through JPEG at quality
// Q (1-100, 4:2:0 chroma) before tracking: what a camera's MJPEG or a lossy recording does.
#include "face_crossing.hpp"
#include "metrics/metrics.hpp"
#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace {

struct StudyOptions {
    gc::sim::Preset preset;
    int first = 0, last = 0;
    int particles = 1000;
    gc::Eye eye = gc::Eye::Left;
    bool trace = false;
    bool learned = false;  // the learned detector instead of the thesis's motion detector
    int jpeg_quality = 0;  // 0: frames as rendered
};

// The options from the command line; nothing when they are wrong.
std::optional<StudyOptions> parse_options(int argc, char** argv)
{
    const auto preset = gc::sim::preset_from_string(argv[1]);
    StudyOptions o;
    o.first = std::atoi(argv[2]);
    o.last = std::atoi(argv[3]);
    o.particles = argc > 4 ? std::atoi(argv[4]) : 1000;
    const std::string eye_name = argc > 5 ? argv[5] : "left";
    bool options_ok = true;
    for (int i = 6; i < argc; ++i) {
        const std::string option = argv[i];
        if (option == "trace") {
            o.trace = true;
        } else if (option == "learned") {
            o.learned = true;
        } else if (option.rfind("jpeg=", 0) == 0) {
            o.jpeg_quality = std::atoi(option.c_str() + 5);
            options_ok = options_ok && o.jpeg_quality >= 1 && o.jpeg_quality <= 100;
        } else {
            options_ok = false;
        }
    }
    o.eye = eye_name == "right" ? gc::Eye::Right : gc::Eye::Left;
    if (!preset || o.first < 0 || o.last < o.first || o.particles < 1 || !options_ok ||
        (eye_name != "left" && eye_name != "right"))
        return std::nullopt;
    o.preset = *preset;
    return o;
}

// One seed's 200 frames: the SNR and how the tracker fared while the hand crossed the face.
struct SeedFigures {
    double snr_db = 0.0;
    int crossing = 0, off = 0, lost = 0;
    double entry_iou = -1.0;
};

SeedFigures track_seed(const StudyOptions& o, int seed)
{
    gc::sim::SceneConfig cfg;
    cfg.preset = o.preset;
    cfg.motion = gc::sim::Motion::Mixed;
    cfg.seed = static_cast<std::uint64_t>(seed);
    const gc::sim::Scene scene(cfg);
    gc::TrackerParams params;
    params.detector = o.learned ? gc::HandDetector::Learned : gc::HandDetector::Motion;
    params.particles = o.particles;
    params.seed = cfg.seed;
    gc::HandTracker tracker(params);
    cv::Mat bgr;
    gc::sim::EyeTruth truth;
    gc::SnrAccumulator snr;
    SeedFigures r;
    for (int f = 0; f < 200; ++f) {
        scene.render(f, o.eye, {}, bgr, &truth);
        if (o.jpeg_quality > 0) {
            std::vector<uchar> encoded;
            cv::imencode(".jpg", bgr, encoded, {cv::IMWRITE_JPEG_QUALITY, o.jpeg_quality});
            bgr = cv::imdecode(encoded, cv::IMREAD_COLOR);
        }
        const auto& e = tracker.process(bgr);
        const cv::Mat1b tracked = e.valid() ? gc::contour_mask(e.contour, bgr.size()) : cv::Mat1b(bgr.size(), uchar(0));
        snr.add(truth.mask, tracked);
        const bool crosses = gc_test::hand_crosses_face(truth);
        if (o.trace)
            std::printf("  frame %3d %s conf %.2f iou %.2f scale %.2f hand %d%s\n", f, e.valid() ? "track" : "acq  ",
                        e.confidence, e.valid() ? gc::mask_iou(truth.mask, tracked) : 0.0, e.mean.scale,
                        cv::countNonZero(truth.mask), crosses ? " face" : "");
        if (!crosses) continue;
        ++r.crossing;
        r.off += !gc_test::on_the_hand(e, truth, tracked);
        r.lost += !e.valid();
        if (r.entry_iou < 0.0) r.entry_iou = e.valid() ? gc::mask_iou(truth.mask, tracked) : 0.0;
    }
    r.snr_db = snr.snr_db();
    return r;
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 4) {
        std::fprintf(stderr,
                     "usage: %s PRESET FIRST_SEED LAST_SEED [PARTICLES [left|right [trace] [learned] [jpeg=Q]]]\n",
                     argv[0]);
        return 2;
    }
    const std::optional<StudyOptions> options = parse_options(argc, argv);
    if (!options) {
        std::fprintf(stderr, "%s: bad arguments\n", argv[0]);
        return 2;
    }
    double snr_sum = 0.0;
    int seeds = 0, crossing_seeds = 0, kept = 0, failed_after_good_entry = 0;
    for (int seed = options->first; seed <= options->last; ++seed) {
        const SeedFigures r = track_seed(*options, seed);
        snr_sum += r.snr_db;
        ++seeds;
        if (r.crossing > 10) {
            ++crossing_seeds;
            kept += r.off == 0;
            failed_after_good_entry += r.off > 0 && r.entry_iou >= 0.5;
        }
        std::printf("seed %d snr %.2f crossing %d off %d lost %d entry %.2f\n", seed, r.snr_db, r.crossing, r.off,
                    r.lost, std::max(r.entry_iou, 0.0));
        std::fflush(stdout);
    }
    std::printf("mean snr %.3f dB over %d seeds; hand kept through the face on %d of %d crossing seeds"
                " (of the others, %d were on the hand as the crossing began)\n",
                snr_sum / seeds, seeds, kept, crossing_seeds, failed_after_good_entry);
    return 0;
}
