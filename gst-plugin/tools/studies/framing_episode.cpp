#include "framing_episode.hpp"

#include "running_head.hpp"
#include "sim/scene.hpp"
#include "stereo/calibration.hpp"
#include "stereo/director_mount.hpp"
#include "stereo/head_geometry.hpp"
#include "stereo/pointing_dwell.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <gst/gst.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gc::study {
namespace {

constexpr double kFps = 30.0;
constexpr int kWidth = 640, kHeight = 480;

// Where the target should show, relative to the palm's line of sight once fixate has centred
// the hand (degrees: right, up): both sides, above and below, inside the 60 x 47 deg view.
constexpr double kDirections[][2] = {{22, 6}, {-22, 6}, {20, -5}, {-20, -5}, {24, 0}, {-24, 0}};

// The director of the study: 300 mm above the head's neck axis and 200 mm behind it, facing
// ahead, a 1920x1080 picture 60 deg across at its widest.
DirectorMount study_director()
{
    DirectorMount d;
    d.head_to_base.t = {0.0, 300.0, 200.0};
    return d;
}

// The point the hand aims at: the target-distance point of a ray from the palm that shows
// at the episode's direction from the palm's line of sight (with a director: in the
// direction of kSideDirections).
cv::Vec3d aim_for(const Episode& e)
{
    sim::SceneConfig c;
    c.preset = sim::Preset::Light;
    c.motion = sim::Motion::Static;
    c.seed = e.seed;
    const cv::Vec3d palm = sim::Scene(c).hand_pose(int(2.0 * kFps)).palm_mm;
    if (e.director) {
        const auto& d = kSideDirections[std::size_t(e.direction) % std::size(kSideDirections)];
        return palm + e.target_distance_mm * (rotation_about_y(d[0]) * rotation_about_x(d[1]) * cv::Vec3d(0, 0, 1));
    }
    const auto& d = kDirections[std::size_t(e.direction) % std::size(kDirections)];
    const cv::Vec3d w = rotation_about_y(d[0]) * rotation_about_x(d[1]) * (palm * (1.0 / cv::norm(palm)));
    // The point s w whose distance from the palm is target-distance.
    const double b = w.dot(palm);
    const double s = b + std::sqrt(b * b - palm.dot(palm) + e.target_distance_mm * e.target_distance_mm);
    return s * w;
}

// The default rig with the study's director, written where handtracker can read it.
std::string director_calibration()
{
    StereoCalibration cal = default_calibration(cv::Size(kWidth, kHeight));
    cal.director = study_director();
    const std::string path = (std::filesystem::temp_directory_path() / "framing_study_director.yml").string();
    save_calibration(cal, path);
    return path;
}

std::string pipeline_for(const Episode& e, const std::string& head, const cv::Vec3d& aim,
                         const std::string& director = {})
{
    char aim_text[96];
    std::snprintf(aim_text, sizeof aim_text, "\"<%.1f, %.1f, %.1f>\"", aim[0], aim[1], aim[2]);
    const std::string caps = "video/x-raw,width=640,height=480,framerate=30/1";
    auto eye = [&](const char* name, bool truth) {
        return std::string("handscenesrc name=") + name + " eye=" + name + " is-live=true head=" + head +
               " scene=light motion=static seed=" + std::to_string(e.seed) + " aim=" + aim_text +
               " num-buffers=" + std::to_string(int(e.seconds * kFps)) +
               " truth-messages=" + (truth ? "true" : "false") + " ! " + caps;
    };
    const std::string framing = director.empty()
                                    ? " output=attended"
                                    : " output=left director=" + director + " calibration=" + director_calibration();
    return eye("left", true) + " ! t.sink_left " + eye("right", false) +
           " ! t.sink_right handtracker name=t head=" + head + " steer=fixate" + framing +
           " dwell=1 target-distance=" + std::to_string(e.target_distance_mm) +
           " target-region=" + std::to_string(e.region_mm) + " ! " + caps + " ! fakesink sync=false";
}

struct OutputFrame {
    GstClockTime pts = GST_CLOCK_TIME_NONE;
    guint64 frame = 0;      // the stereo pair's index: a frame output twice counts once
    bool pointing = false;  // a 3D ray
    bool tracked = false;
    cv::Rect view;
};

struct Truth {
    cv::Vec3d fingertip, direction;
    HeadPose pose;
};

GstPadProbeReturn on_output(GstPad*, GstPadProbeInfo* info, gpointer data)
{
    GstBuffer* buffer = GST_PAD_PROBE_INFO_BUFFER(info);
    OutputFrame f;
    f.pts = GST_BUFFER_PTS(buffer);
    if (const GstHandPointingMeta* m = gst_buffer_get_hand_pointing_meta(buffer)) {
        f.tracked = m->state == GST_HAND_POINTING_STATE_TRACKING;
        f.frame = m->frame;
        f.pointing = m->flags & GST_HAND_POINTING_FLAG_HAS_3D;
        f.view = {m->view_x, m->view_y, m->view_width, m->view_height};
    }
    static_cast<std::vector<OutputFrame>*>(data)->push_back(f);
    return GST_PAD_PROBE_OK;
}

cv::Vec3d vec3(const GstStructure* s, const char* field)
{
    cv::Vec3d out;
    const GValue* v = gst_structure_get_value(s, field);
    for (guint i = 0; v && i < 3; ++i) out[int(i)] = g_value_get_double(gst_value_array_get_value(v, i));
    return out;
}

Truth truth_of(const GstStructure* s)
{
    Truth t;
    t.fingertip = vec3(s, "fingertip-head-mm");
    t.direction = vec3(s, "direction-head");
    gst_structure_get_double(s, "head-pan-deg", &t.pose.pan_deg);
    gst_structure_get_double(s, "head-tilt-deg", &t.pose.tilt_deg);
    gst_structure_get_double(s, "head-verge-left-deg", &t.pose.verge_left_deg);
    gst_structure_get_double(s, "head-verge-right-deg", &t.pose.verge_right_deg);
    gst_structure_get_double(s, "head-zoom", &t.pose.zoom);
    return t;
}

struct Collected {
    std::vector<OutputFrame> frames;
    std::map<GstClockTime, Truth> truth;              // the left eye's, by timestamp
    std::optional<GstClockTime> pick;                 // the first pick's timestamp
    cv::Vec3d picked;                                 // ...and the target it picked (head frame, mm)
    std::chrono::steady_clock::time_point pick_seen;  // when its message came off the bus
    std::string error;
};

// The director's pose as its simulated head reports it, sampled every 10 ms on a thread of its
// own from construction to stop().
class DirectorSamples {
public:
    using Clock = std::chrono::steady_clock;
    explicit DirectorSamples(headctl::HeadServer& head) : thread_([this, &head] { run(head); }) {}
    ~DirectorSamples() { stop(); }
    void stop()
    {
        stopping_ = true;
        if (thread_.joinable()) thread_.join();
    }
    std::vector<std::pair<Clock::time_point, HeadPose>> samples() const
    {
        std::lock_guard lock(mutex_);
        return samples_;
    }

private:
    void run(headctl::HeadServer& head)
    {
        while (!stopping_) {
            head.with_model([this](headctl::HeadModel& model, double now_s) {
                const HeadPose pose = model.state(now_s).pose;
                std::lock_guard lock(mutex_);
                samples_.emplace_back(Clock::now(), pose);
            });
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }

    mutable std::mutex mutex_;
    std::vector<std::pair<Clock::time_point, HeadPose>> samples_;
    std::atomic<bool> stopping_{false};
    std::thread thread_;
};

// Runs the pipeline to its end, gathering the output frames, the truth and the first pick.
void run_pipeline(const std::string& description, double seconds, Collected& out)
{
    GError* err = nullptr;
    GstElement* pipeline = gst_parse_launch(description.c_str(), &err);
    if (!pipeline) {
        out.error = err ? err->message : "cannot build the pipeline";
        g_clear_error(&err);
        return;
    }
    GstElement* tracker = gst_bin_get_by_name(GST_BIN(pipeline), "t");
    GstPad* src = gst_element_get_static_pad(tracker, "src");
    gst_pad_add_probe(src, GST_PAD_PROBE_TYPE_BUFFER, on_output, &out.frames, nullptr);
    gst_object_unref(src);
    gst_object_unref(tracker);
    GstBus* bus = gst_element_get_bus(pipeline);
    gst_element_set_state(pipeline, GST_STATE_PLAYING);
    const auto types = GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_ELEMENT);
    while (GstMessage* m = gst_bus_timed_pop_filtered(bus, GstClockTime((seconds + 30.0) * GST_SECOND), types)) {
        const GstStructure* s = gst_message_get_structure(m);
        const std::string from = GST_OBJECT_NAME(GST_MESSAGE_SRC(m));
        bool done = GST_MESSAGE_TYPE(m) == GST_MESSAGE_EOS;
        if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR) {
            GError* e = nullptr;
            gst_message_parse_error(m, &e, nullptr);
            out.error = e ? e->message : "error";
            g_clear_error(&e);
            done = true;
        } else if (s && gst_structure_has_name(s, "hand-truth") && from == "left") {
            guint64 ts = 0;
            gst_structure_get_uint64(s, "timestamp", &ts);
            out.truth[ts] = truth_of(s);
        } else if (s && gst_structure_has_name(s, "attended-target") && !out.pick &&
                   g_strcmp0(gst_structure_get_string(s, "event"), "picked") == 0) {
            guint64 ts = 0;
            gst_structure_get_uint64(s, "timestamp", &ts);
            out.pick = ts;
            out.picked = vec3(s, "target-head-mm");
            out.pick_seen = std::chrono::steady_clock::now();
        }
        gst_message_unref(m);
        if (done) break;
    }
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(bus);
    gst_object_unref(pipeline);
}

// Where the true target lies in the crop `view`: its centre as a fraction of the crop's width
// and height, and the region's width as a fraction of the crop's.
std::optional<cv::Vec3d> placement(const cv::Rect& view, const Truth& t, const Episode& e, const StereoCalibration& cal)
{
    const cv::Vec3d target = t.fingertip + e.target_distance_mm * t.direction;
    const auto region = region_in_left_view(target, e.region_mm, cal, t.pose);
    if (!region || view.width <= 0 || view.height <= 0) return std::nullopt;
    return cv::Vec3d((region->centre.x - view.x) / view.width, (region->centre.y - view.y) / view.height,
                     region->width_px / view.width);
}

// In the central third, filling 75-125 % of the width.
bool framed(const std::optional<cv::Vec3d>& p)
{
    auto third = [](double v) { return v > 1.0 / 3 && v < 2.0 / 3; };
    return p && third((*p)[0]) && third((*p)[1]) && (*p)[2] >= 0.75 && (*p)[2] <= 1.25;
}

// How far the picked target lies from the true one as the left eye sees them at the pick
// (degrees: right, down).
cv::Vec2d pick_error(const cv::Vec3d& picked, const Truth& t, const Episode& e, const StereoCalibration& cal)
{
    const RigidTransform to_left = camera_to_head(cal.head, t.pose, Eye::Left).inverse();
    const cv::Vec3d a = to_left.apply(picked), b = to_left.apply(t.fingertip + e.target_distance_mm * t.direction);
    const double deg = 180.0 / CV_PI;
    return {(std::atan2(a[0], a[2]) - std::atan2(b[0], b[2])) * deg,
            (std::atan2(a[1], a[2]) - std::atan2(b[1], b[2])) * deg};
}

// The truth of the left frame nearest `pts`: the output's timestamps run on a regular grid
// from 0, the live eyes' at their capture times, within a frame of the output that took them.
const Truth* truth_at(const std::map<GstClockTime, Truth>& truth, GstClockTime pts)
{
    const GstClockTime frame = GstClockTime(GST_SECOND / kFps);
    const Truth* best = nullptr;
    GstClockTime best_gap = frame;
    for (auto it = truth.lower_bound(pts > frame ? pts - frame : 0); it != truth.end() && it->first < pts + frame;
         ++it) {
        const GstClockTime gap = it->first > pts ? it->first - pts : pts - it->first;
        if (gap < best_gap) best = &it->second, best_gap = gap;
    }
    return best;
}

// The crop of each output frame from the pick on, against the truth of its frame.
void score_crop(const Episode& e, const Collected& c, EpisodeResult& r)
{
    const StereoCalibration cal = default_calibration(cv::Size(kWidth, kHeight));
    if (const Truth* t = truth_at(c.truth, *c.pick)) r.pick_error_deg = pick_error(c.picked, *t, e, cal);
    GstClockTime framed_from = GST_CLOCK_TIME_NONE;
    for (const OutputFrame& f : c.frames) {
        if (f.pts < *c.pick) continue;
        const Truth* t = truth_at(c.truth, f.pts);
        if (!t) continue;  // nothing to judge it by (the eyes' last frames came out already)
        const std::optional<cv::Vec3d> p = placement(f.view, *t, e, cal);
        if (p) r.last_placement = *p;
        if (!framed(p))
            framed_from = GST_CLOCK_TIME_NONE;  // framed means framed on every frame since
        else if (framed_from == GST_CLOCK_TIME_NONE)
            framed_from = f.pts;
    }
    if (framed_from != GST_CLOCK_TIME_NONE) r.framed_after_s = double(framed_from - *c.pick) / GST_SECOND;
}

// The director's picture at each sampled pose from the pick's message on (the hand is held
// still, so the target is the one true at the pick).
void score_director(const Episode& e, const Collected& c, const DirectorSamples& director, EpisodeResult& r)
{
    const Truth* t = truth_at(c.truth, *c.pick);
    if (!t) return;
    const DirectorMount mount = study_director();
    const cv::Vec3d truth = t->fingertip + e.target_distance_mm * t->direction;
    const HeadPose aimed = director_aim(mount, c.picked, e.region_mm, 1.0, 1.0);
    const HeadPose true_aim = director_aim(mount, truth, e.region_mm, 1.0, 1.0);
    r.pick_error_deg = {aimed.pan_deg - true_aim.pan_deg, true_aim.tilt_deg - aimed.tilt_deg};
    std::optional<DirectorSamples::Clock::time_point> framed_from;
    for (const auto& [time, pose] : director.samples()) {
        if (time < c.pick_seen) continue;
        const auto placed = place_in_director(mount, pose, truth, e.region_mm);
        std::optional<cv::Vec3d> p;
        if (placed) p = cv::Vec3d(placed->centre.x, placed->centre.y, placed->fill);
        if (p) r.last_placement = *p;
        if (!framed(p))
            framed_from.reset();
        else if (!framed_from)
            framed_from = time;
    }
    if (framed_from) r.framed_after_s = std::chrono::duration<double>(*framed_from - c.pick_seen).count();
}

}  // namespace

EpisodeResult run_episode(const Episode& e)
{
    EpisodeResult r;
    const cv::Vec3d aim = aim_for(e);
    char text[96];
    std::snprintf(text, sizeof text, "aim <%.0f, %.0f, %.0f>", aim[0], aim[1], aim[2]);
    r.aim = text;
    Collected c;
    loopback::RunningHead head(loopback::loopback_head());
    std::optional<loopback::RunningHead> director;
    std::optional<DirectorSamples> director_poses;
    if (e.director) {
        director.emplace(loopback::loopback_head());
        director_poses.emplace(director->server());
    }
    run_pipeline(pipeline_for(e, head.uri(), aim, director ? director->uri() : std::string()), e.seconds, c);
    if (director_poses) director_poses->stop();
    r.error = c.error;
    std::map<guint64, std::pair<bool, bool>> pairs;  // tracked, a 3D ray: per stereo pair
    for (const OutputFrame& f : c.frames) {
        auto& [tracked, pointing] = pairs[f.frame];
        tracked = tracked || f.tracked;
        pointing = pointing || f.pointing;
    }
    r.frames = int(pairs.size());
    for (const auto& [frame, seen] : pairs) r.tracked += seen.first, r.pointing += seen.second;
    if (!c.pick || c.frames.empty()) return r;
    r.picked = true;
    r.pick_s = double(GstClockTimeDiff(*c.pick - c.frames.front().pts)) / GST_SECOND;
    if (director_poses)
        score_director(e, c, *director_poses, r);
    else
        score_crop(e, c, r);
    return r;
}

}  // namespace gc::study
