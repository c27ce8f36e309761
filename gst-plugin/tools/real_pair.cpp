#include "tools/real_pair.hpp"

#include "sim/appearance.hpp"
#include "sim/camera_effects.hpp"
#include "stereo/calibration.hpp"
#include "tools/bench_stats.hpp"
#include "tools/gst_frame_reader.hpp"
#include "tools/json_reader.hpp"
#include "tracker/pointing_tracker.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace gc::tools {

namespace {

JsonValue read_json(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::stringstream text;
    text << in.rdbuf();
    return JsonReader::parse(text.str());
}

cv::Point2d point_of(const JsonValue& v) { return {v[0].number(), v[1].number()}; }
cv::Vec3d vec_of(const JsonValue& v) { return {v[0].number(), v[1].number(), v[2].number()}; }

// Reference index fingertips of one view, by frame; frames without a hand are absent.
std::map<int, cv::Point2d> view_reference(const std::string& path)
{
    std::map<int, cv::Point2d> tips;
    const std::vector<ReferenceHand> hands = read_reference_hands(path);
    for (std::size_t i = 0; i < hands.size(); ++i)
        if (hands[i]) tips[int(i)] = (*hands[i])[8];
    return tips;
}

struct StereoReference {
    bool pointing = false;
    cv::Vec3d direction;
};

std::map<int, StereoReference> stereo_reference(const std::string& path)
{
    std::map<int, StereoReference> out;
    const JsonValue doc = read_json(path);
    for (const JsonValue& f : doc["frames"].array())
        out[int(f["frame"].number())] = {std::get<bool>(f["pointing"].v), vec_of(f["direction"])};
    return out;
}

double quantile(std::vector<double> v, double q)
{
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

double share(int part, int whole) { return whole > 0 ? double(part) / whole : 0.0; }

// Per-view tallies while the frames go by.
struct ViewTally {
    std::vector<double> errors, on_models, carried, pointing_errors;
    int reference = 0, pointing_reference = 0, near = 0, tracked = 0, models = 0;

    void add(const EyeEstimate& e, const std::optional<cv::Point2d>& tip, bool pointing)
    {
        if (e.valid()) {
            ++tracked;
            models += e.models_ran;
        }
        if (!tip) return;
        ++reference;
        pointing_reference += pointing;
        if (!e.valid()) return;
        const double error = cv::norm(cv::Point2d(e.fingertip) - *tip);
        errors.push_back(error);
        (e.models_ran ? on_models : carried).push_back(error);
        if (pointing) pointing_errors.push_back(error);
        near += error <= 30.0;
    }

    ViewFigures figures() const
    {
        ViewFigures f;
        f.reference_frames = reference;
        f.coverage = share(int(errors.size()), reference);
        f.within_30px = share(near, reference);
        f.median_px = quantile(errors, 0.5);
        f.median_px_models = quantile(on_models, 0.5);
        f.median_px_carried = quantile(carried, 0.5);
        f.models_share = share(models, tracked);
        f.pointing_frames = pointing_reference;
        f.pointing_coverage = share(int(pointing_errors.size()), pointing_reference);
        f.pointing_median_px = quantile(pointing_errors, 0.5);
        return f;
    }
};

// The next frame of a view; false at its end. The committed pair decodes whole, so a frame
// it cannot decode means a broken copy.
bool read_frame(GstFrameReader& view, cv::Mat& bgr, const std::string& path)
{
    const FrameStatus status = view.read(bgr);
    if (status == FrameStatus::Undecodable) throw std::runtime_error("cannot decode a frame of " + path);
    return status == FrameStatus::Frame;
}

// What the options do to each decoded frame: dimming first, then the bright window, then
// the rendered scenes' camera noise (the same in every run).
class PictureChange {
public:
    PictureChange(cv::Size frame, double dim, double noise_sd, bool bright_window = false)
        : bright_window_(bright_window)
    {
        if (!(dim > 0.0 && dim <= 1.0)) throw std::invalid_argument("real pair: dim must lie in (0, 1]");
        if (dim < 1.0) {
            levels_ = cv::Mat1b(1, 256);
            for (int v = 0; v < 256; ++v)
                levels_.at<uchar>(0, v) = cv::saturate_cast<uchar>(255.0 * dim * std::pow(v / 255.0, 2.2));
        }
        constexpr std::uint64_t kNoiseSeed = 0x6E6F697365ULL;
        if (noise_sd > 0.0) noise_ = sim::SensorNoise(frame, noise_sd, kNoiseSeed);
    }

    // Frame `i` of view `view` (0 left, 1 right) takes its own window of the noise's pool.
    void apply(cv::Mat& bgr, int i, int view) const
    {
        if (!levels_.empty()) cv::LUT(bgr, levels_, bgr);
        if (bright_window_) bgr(kBrightWindows[view] & cv::Rect(0, 0, bgr.cols, bgr.rows)).setTo(cv::Scalar::all(255));
        noise_.apply(bgr, sim::mix_seed(std::uint64_t(i) << 1 | std::uint64_t(view), 0));
    }

private:
    cv::Mat levels_;  // empty: no dimming
    bool bright_window_;
    sim::SensorNoise noise_;
};

}  // namespace

std::vector<ReferenceHand> read_reference_hands(const std::string& path)
{
    std::vector<ReferenceHand> hands;
    const JsonValue doc = read_json(path);
    for (const JsonValue& frame : doc["frames"].array()) {
        if (!frame.has("landmarks") || frame["landmarks"].is_null() || frame["landmarks"].array().size() != 21) {
            hands.emplace_back();
            continue;
        }
        std::array<cv::Point2d, 21> hand;
        for (int k = 0; k < 21; ++k) hand[k] = point_of(frame["landmarks"][k]);
        hands.emplace_back(hand);
    }
    return hands;
}

RealPairFigures measure_real_pair(const RealPairOptions& o)
{
    const std::string base = o.dir + "/handpose3d_";
    const auto left_ref = view_reference(base + "cam0.mediapipe.json");
    const auto right_ref = view_reference(base + "cam1.mediapipe.json");
    const auto stereo_ref = stereo_reference(base + "ref3d.json");
    // Decoded as gesturecam-track and the element decode them (GStreamer, then the element's
    // colour conversion), so the figures are the product's.
    GstFrameReader left(base + "cam0.mp4"), right(base + "cam1.mp4");
    const StereoCalibration calibration = load_calibration(base + "calib.yml");
    PointingTracker tracker(o.params, calibration);

    ViewTally lt, rt;
    std::vector<double> angles, ms, cpu_ms;
    int pointing = 0, other = 0, false_rays = 0, frame = 0;
    const cv::Size frame_size = calibration.image_size;
    const PictureChange change(frame_size, o.dim, o.noise_sd, o.bright_window);
    cv::Mat l, r;
    for (; frame < o.last_frame && read_frame(left, l, base + "cam0.mp4") && read_frame(right, r, base + "cam1.mp4");
         ++frame) {
        if (frame < o.first_frame) continue;
        if (l.size() != frame_size || r.size() != frame_size)
            throw std::runtime_error("real pair: the frames are not the calibration's size");
        change.apply(l, frame, 0);
        change.apply(r, frame, 1);
        const auto t0 = BenchClock::now();
        const double cpu0 = process_cpu_ms();
        const FrameResult& res = tracker.process_stereo(l, r);
        cpu_ms.push_back(process_cpu_ms() - cpu0);
        ms.push_back(ms_since(t0));
        const auto ref = stereo_ref.find(frame);
        const bool points = ref != stereo_ref.end() && ref->second.pointing;
        const auto tip = [&](const std::map<int, cv::Point2d>& m) {
            const auto it = m.find(frame);
            return it == m.end() ? std::nullopt : std::optional<cv::Point2d>(it->second);
        };
        lt.add(res.left, tip(left_ref), points);
        rt.add(res.right, tip(right_ref), points);
        if (ref == stereo_ref.end()) continue;
        if (points) {
            ++pointing;
            if (res.pointing.valid) angles.push_back(angle_deg(res.pointing.direction, ref->second.direction));
        } else {
            ++other;
            false_rays += res.pointing.valid;
        }
    }
    RealPairFigures f;
    f.frames = frame - o.first_frame;
    f.left = lt.figures();
    f.right = rt.figures();
    f.pointing_frames = pointing;
    f.ray_coverage = share(int(angles.size()), pointing);
    f.angle_median_deg = quantile(angles, 0.5);
    f.angle_p90_deg = quantile(angles, 0.9);
    f.other_frames = other;
    f.false_pointing = share(false_rays, other);
    f.ms_per_frame = quantile(ms, 0.5);
    f.cpu_ms_per_frame = quantile(cpu_ms, 0.5);
    return f;
}

// Frame pixels -> view pixels for frame i: the window, moved by its sway at i / 30 s
// (seeded by nothing: the same path every run), scaled to the view.
cv::Matx23d window_map(const RealCropOptions& o, int i)
{
    const double t = i / 30.0, two_pi = 2.0 * CV_PI;
    const CameraSway& w = o.sway;
    const cv::Point2d centre(o.window.x + 0.5 * o.window.width + w.drift_px * std::sin(two_pi * 0.31 * t) +
                                 w.bob_px * std::sin(two_pi * 1.7 * t + 0.5),
                             o.window.y + 0.5 * o.window.height + w.drift_px * std::sin(two_pi * 0.23 * t + 1.0) +
                                 w.bob_px * std::sin(two_pi * 2.1 * t));
    const double roll = w.roll_deg * std::sin(two_pi * 0.19 * t + 2.0) * CV_PI / 180.0;
    const double sx = double(o.size.width) / o.window.width, sy = double(o.size.height) / o.window.height;
    const double c = std::cos(roll), s = std::sin(roll);
    // view = S R (frame - centre) + size / 2
    const cv::Matx22d A(sx * c, sx * s, -sy * s, sy * c);
    const cv::Vec2d b = cv::Vec2d(0.5 * o.size.width, 0.5 * o.size.height) - A * cv::Vec2d(centre.x, centre.y);
    return {A(0, 0), A(0, 1), b[0], A(1, 0), A(1, 1), b[1]};
}

// The window's reach in the frame at the largest sway: throws std::invalid_argument when it
// leaves the frame.
void check_window(const RealCropOptions& o, cv::Size frame)
{
    const double roll = std::abs(o.sway.roll_deg) * CV_PI / 180.0;
    const int margin = int(std::ceil(std::abs(o.sway.drift_px) + std::abs(o.sway.bob_px) +
                                     0.5 * std::hypot(o.window.width, o.window.height) * std::sin(roll)));
    const cv::Rect reach(o.window.x - margin, o.window.y - margin, o.window.width + 2 * margin,
                         o.window.height + 2 * margin);
    if ((cv::Rect(cv::Point(), frame) & reach) != reach)
        throw std::invalid_argument("real crop: the window lies outside the " + std::to_string(frame.width) + "x" +
                                    std::to_string(frame.height) + " frames");
}

RealCropOptions window_options(const std::string& dir, const NamedWindow& window)
{
    RealCropOptions o;
    o.dir = dir;
    o.camera = window.camera;
    o.window = window.window;
    o.sway = window.sway;
    return o;
}

RealCropFigures measure_real_crop(const RealCropOptions& o)
{
    const std::string name = "handpose3d_cam" + std::to_string(o.camera);
    const std::vector<ReferenceHand> hands = read_reference_hands(o.dir + "/" + name + ".mediapipe.json");
    const auto stereo_ref = stereo_reference(o.dir + "/handpose3d_ref3d.json");
    const std::string video = o.dir + "/" + name + ".mp4";
    GstFrameReader reader(video);
    HandTracker tracker(o.params);
    cv::Matx23d map;
    const auto into_window = [&](const cv::Point2d& p) { return cv::Point2d(map * cv::Vec3d(p.x, p.y, 1.0)); };
    const cv::Rect2d seen(0, 0, o.size.width, o.size.height);
    ViewTally tally;
    int cut = 0;
    const PictureChange change(o.size, o.dim, o.noise_sd);
    cv::Mat frame, view;
    for (int i = 0; i < o.last_frame && read_frame(reader, frame, video); ++i) {
        if (i < o.first_frame) continue;
        check_window(o, frame.size());
        map = window_map(o, i);
        if (o.sway.still())
            cv::resize(frame(o.window), view, o.size, 0.0, 0.0, cv::INTER_AREA);
        else
            cv::warpAffine(frame, view, map, o.size, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        change.apply(view, i, 0);
        const EyeEstimate& e = tracker.process(view);
        std::optional<cv::Point2d> tip;
        if (std::size_t(i) < hands.size() && hands[i]) {
            int inside = 0;
            for (const cv::Point2d& p : *hands[i]) inside += seen.contains(into_window(p));
            const cv::Point2d t = into_window((*hands[i])[8]);
            if (seen.contains(t) && 2 * inside >= int(hands[i]->size())) {
                tip = t;
                cut += inside < int(hands[i]->size());
            }
        }
        const auto ref = stereo_ref.find(i);
        tally.add(e, tip, ref != stereo_ref.end() && ref->second.pointing);
    }
    return {tally.figures(), cut};
}

}  // namespace gc::tools
