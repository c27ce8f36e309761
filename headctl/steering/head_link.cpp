#include "headctl/steering/head_link.hpp"

#include "stereo/camera_motion.hpp"
#include "stereo/extrinsics.hpp"
#include "stereo/head_geometry.hpp"
#include "stereo/pointing_dwell.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace gc::headctl {

namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Smoothing of the hand's angular velocity (feed-forward); per frame, 1 = no smoothing.
constexpr double kRateSmoothing = 0.3;

double clamp_to(const headctl::AxisLimits& l, double deg, double margin)
{
    return std::clamp(deg, l.min_deg + margin, l.max_deg - margin);
}

// Pan and tilt that turn the head's forward axis (through the neck origin) towards a head
// frame point; the eyes' small offsets from that axis are left to the vergence.
std::pair<double, double> aim_at(const cv::Vec3d& target, const HeadGeometry& g)
{
    const double pan = std::atan2(target[0], target[2]) * kRadToDeg;
    const cv::Vec3d q = rotation_about_y(pan).t() * target - g.tilt_centre_mm;
    const double tilt = std::atan2(-q[1], q[2]) * kRadToDeg;
    return {pan, tilt};
}

// A head-frame point in eye E's camera frame at pan/tilt with that eye not verged.
cv::Vec3d in_unverged_eye(const HeadGeometry& g, const HeadPose& pose, Eye eye, const cv::Vec3d& point)
{
    HeadPose p = pose;
    p.verge_left_deg = 0.0;
    p.verge_right_deg = 0.0;
    return camera_to_head(g, p, eye).inverse().apply(point);
}

// Point mode's target placement, checked where the configuration is made and where it changes.
void check_target(const TargetPlacement& target)
{
    if (!(std::isfinite(target.distance_mm) && target.distance_mm > 0.0))
        throw std::invalid_argument("head link: target distance must be finite and > 0 mm");
}

}  // namespace

std::string_view to_string(SteerMode mode)
{
    switch (mode) {
    case SteerMode::Off:
        return "off";
    case SteerMode::Fixate:
        return "fixate";
    case SteerMode::Point:
        return "point";
    }
    return "unknown";
}

std::optional<SteerMode> steer_mode_from_string(std::string_view name)
{
    for (SteerMode m : {SteerMode::Off, SteerMode::Fixate, SteerMode::Point})
        if (to_string(m) == name) return m;
    return std::nullopt;
}

std::string_view to_string(SteeringEvent event)
{
    switch (event) {
    case SteeringEvent::Look:
        return "look";
    case SteeringEvent::Return:
        return "return";
    case SteeringEvent::Follow:
        return "follow";
    case SteeringEvent::ManualPause:
        return "manual-pause";
    case SteeringEvent::Resume:
        return "resume";
    }
    return "unknown";
}

void SteeringTimes::validate() const
{
    auto check = [](double v, bool ok, const char* what) {
        if (!std::isfinite(v) || !ok) throw std::invalid_argument(std::string("head link: ") + what);
    };
    check(dwell_s, dwell_s > 0.0, "dwell time must be finite and > 0 s");
    check(look_s, look_s > 0.0, "look time must be finite and > 0 s");
    check(manual_pause_s, manual_pause_s >= 0.0, "manual pause must be finite and >= 0 s");
}

void HeadLinkConfig::validate() const
{
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (uri.empty()) throw std::invalid_argument("head link: the head URI is empty");
    check_target(target);
    if (!positive(nominal_depth_mm)) throw std::invalid_argument("head link: nominal depth must be finite and > 0 mm");
    if (!positive(vergence_gain_per_s)) throw std::invalid_argument("head link: vergence gain must be finite and > 0");
    if (!std::isfinite(vergence_dead_band_deg) || vergence_dead_band_deg < 0.0)
        throw std::invalid_argument("head link: vergence dead band must be finite and >= 0");
    times.validate();
    point.validate();
    if (reconnect_max.count() <= 0) throw std::invalid_argument("head link: reconnect interval must be > 0");
    if (max_view_age.count() <= 0) throw std::invalid_argument("head link: maximum view age must be > 0");
    fixate.validate();
}

struct HeadLink::Impl {
    HeadLinkConfig config;
    StereoCalibration calibration;
    headctl::FixateController fixate;
    std::optional<headctl::HeadLimits> limits;  // the head's, once it reports them
    std::unique_ptr<headctl::HeadClient> client;

    // The current frame and the one before it.
    std::optional<headctl::Timestamp> capture_time;
    std::optional<HeadPose> capture_pose;
    // Steering's previous step.
    std::optional<headctl::Timestamp> steer_time;
    double view_age_ms = 0.0;  // of the last frame steered from, at end_frame
    bool view_stale = false;

    // Where the hand was last seen, per eye, and its depth along each optical axis.
    std::optional<cv::Point2d> hand_px[2];
    double hand_depth_mm[2];

    // Fixate: the hand's direction (pan, tilt of the left eye's line of sight) and its rate.
    std::optional<std::pair<double, double>> hand_direction;
    double rate_pan_dps = 0.0;
    double rate_tilt_dps = 0.0;
    bool head_has_vergence = true;

    // Point: the dwell that picks targets, how many it had picked, and the plan.
    PointingDwell dwell;
    int dwell_picks = 0;
    headctl::PointDirector director;

    // Someone else moving the head pauses steering until then (seconds on the clock).
    headctl::ManualMoveWatch watch;
    std::optional<double> paused_until_s;
    // Per axis: the last command that named it held it at velocity 0.
    std::array<bool, headctl::kAxisCount> still_sent{};

    Impl(HeadLinkConfig c, StereoCalibration cal)
        : config(std::move(c)), calibration(std::move(cal)),
          fixate(config.fixate), hand_depth_mm{config.nominal_depth_mm, config.nominal_depth_mm},
          director(director_config()), watch(config.manual)
    {
        headctl::HeadClientConfig cc;
        cc.uri = config.uri;
        cc.token = config.token;
        cc.backoff_max = config.reconnect_max;
        cc.backoff_initial = std::min(cc.backoff_initial, config.reconnect_max);
        cc.clock = config.clock;
        cc.on_state_change = config.on_state_change;
        client = std::make_unique<headctl::HeadClient>(std::move(cc));
    }

    headctl::PointDirectorConfig director_config() const
    {
        headctl::PointDirectorConfig pc = config.point;
        pc.look_s = config.times.look_s;
        return pc;
    }

    void report(SteeringEvent event, const std::string& detail) const
    {
        if (config.on_steering) config.on_steering(event, detail);
    }

    // The fixate law starts over from rest where the head is: its memory and the hand's rate
    // are forgotten.
    void restart_fixate()
    {
        hand_direction.reset();
        rate_pan_dps = rate_tilt_dps = 0.0;
        headctl::FixateConfig fc = config.fixate;
        if (limits) fc.limits = *limits;
        fixate = headctl::FixateController(fc);
    }

    // All of steering starts over: point mode's plan and dwell too.
    void restart_steering()
    {
        restart_fixate();
        director.reset();
        dwell = PointingDwell{};
        dwell_picks = 0;
    }

    ImageMotion motion_of(Eye eye, const HeadPose& before, const HeadPose& after) const
    {
        const int i = static_cast<int>(eye);
        const cv::Matx33d& K = eye == Eye::Left ? calibration.M1 : calibration.M2;
        const cv::Point2d at = hand_px[i].value_or(cv::Point2d(K(0, 2), K(1, 2)));
        try {
            return camera_motion(calibration, eye, before, after, at, hand_depth_mm[i]);
        } catch (const std::domain_error&) {
            return {};  // the point left through the back of the camera: nothing to predict
        }
    }

    void remember_hand(const FrameResult& r)
    {
        const EyeEstimate* eyes[2] = {&r.left, &r.right};
        for (int i = 0; i < (r.stereo ? 2 : 1); ++i)
            if (eyes[i]->valid()) hand_px[i] = cv::Point2d(eyes[i]->mean.x, eyes[i]->mean.y);
        if (r.pointing.valid) {
            const HeadPose pose = capture_pose.value_or(HeadPose{});
            hand_depth_mm[0] = r.pointing.palm_mm[2];
            hand_depth_mm[1] = left_to_right_at(calibration, pose).apply(r.pointing.palm_mm)[2];
            for (double& d : hand_depth_mm)
                if (!(d > 0.0)) d = config.nominal_depth_mm;
        }
    }

    void refresh_limits()
    {
        std::optional<headctl::HeadLimits> now = client->limits();
        if (!now || now == limits) return;
        limits = now;
        headctl::FixateConfig fc = config.fixate;
        fc.limits = *now;
        fixate = headctl::FixateController(fc);
    }

    const headctl::AxisLimits& axis_limits(Axis a) const { return limits ? (*limits)[a] : config.fixate.limits[a]; }

    void remember_still(const HeadCommand& command)
    {
        for (Axis a : kAllAxes) {
            bool& still = still_sent[static_cast<std::size_t>(a)];
            if (command.kind == CommandKind::Velocity)
                still = command.values.has(a) ? command.values.get(a) == 0.0 : still;
            else if (command.kind != CommandKind::SavePreset)
                still = false;
        }
    }

    // Submits; a head without vergence axes gets the command without them from then on.
    void submit(HeadCommand command)
    {
        if (!client->has_axis(Axis::Zoom)) command.values.clear(Axis::Zoom);
        if (!head_has_vergence) {
            command.values.clear(Axis::VergeLeft);
            command.values.clear(Axis::VergeRight);
        }
        // A held axis that has just begun to move on no command of ours gets no velocity (the
        // reaction to its picture shifting): the next samples tell whether someone else is
        // moving it (ManualMoveWatch::stirring). Planned moves (looks, returns) go whole.
        if (config.times.manual_pause_s > 0.0 && command.kind == CommandKind::Velocity)
            for (Axis a : {Axis::Pan, Axis::Tilt})
                if (watch.stirring(a)) command.values.clear(a);
        if (command.values.empty() && command.kind != CommandKind::Home && command.kind != CommandKind::Stop &&
            !headctl::is_preset(command.kind))
            return;
        // An axis already told to hold still is not told again, even while the others move:
        // the repeat would cancel a move someone else makes meanwhile (headctl move), which
        // the watch then could not see.
        if (command.kind == CommandKind::Velocity) {
            for (Axis a : kAllAxes)
                if (command.values.has(a) && command.values.get(a) == 0.0 && still_sent[static_cast<std::size_t>(a)])
                    command.values.clear(a);
            if (command.values.empty()) return;
        }
        try {
            client->submit(command);
            remember_still(command);
            watch.commanded(command, to_seconds(client->now()));
            if (config.on_command) config.on_command(command);
        } catch (const std::invalid_argument&) {
            if (!head_has_vergence) throw;
            head_has_vergence = false;
            submit(command);
        }
    }

    // Vergence that makes both lines of sight meet at `depth_mm` straight ahead of the head.
    std::pair<double, double> verge_for_depth(double depth_mm) const
    {
        const double half = 0.5 * calibration.head.baseline_mm();
        const double v = std::atan2(half, depth_mm) * kRadToDeg;
        return {clamp_to(axis_limits(Axis::VergeLeft), v, 0.0), clamp_to(axis_limits(Axis::VergeRight), -v, 0.0)};
    }

    double verge_velocity(Axis axis, double target, double current) const
    {
        const double error = target - current;
        if (std::abs(error) <= config.vergence_dead_band_deg) return 0.0;
        const double vmax = axis_limits(axis).max_velocity_dps;
        return std::clamp(config.vergence_gain_per_s * error, -vmax, vmax);
    }

    void steer_fixate(const FrameResult& r, const HeadPose& capture, const HeadPose& head, double dt)
    {
        headctl::FixateObservation seen;
        if (r.left.valid()) {
            // The angle a pixel offset stands for narrows as the lens zooms in.
            const cv::Matx33d K = zoomed_intrinsics(calibration.M1, capture.zoom);
            seen = headctl::offset_from_image(r.left.mean.x - K(0, 2), r.left.mean.y - K(1, 2), K(0, 0), K(1, 1));
            // The hand's own angular velocity: its line of sight in the head's base frame.
            const std::pair<double, double> direction{capture.pan_deg + capture.verge_left_deg + seen.offset_pan_deg,
                                                      capture.tilt_deg + seen.offset_tilt_deg};
            if (hand_direction) {
                rate_pan_dps += kRateSmoothing * ((direction.first - hand_direction->first) / dt - rate_pan_dps);
                rate_tilt_dps += kRateSmoothing * ((direction.second - hand_direction->second) / dt - rate_tilt_dps);
            }
            hand_direction = direction;
            seen.rate_pan_dps = rate_pan_dps;
            seen.rate_tilt_dps = rate_tilt_dps;
        } else {
            hand_direction.reset();
            rate_pan_dps = rate_tilt_dps = 0.0;
        }
        std::optional<HeadCommand> command = fixate.update(seen, head, dt);
        if (!command) return;
        if (command->kind == CommandKind::Velocity) {
            double vl = 0.0, vr = 0.0;  // hold the vergence while the depth is unknown
            if (r.pointing.valid) {
                const cv::Vec3d& palm = r.pointing.palm_head_mm;
                const double depth = 0.5 * (in_unverged_eye(calibration.head, head, Eye::Left, palm)[2] +
                                            in_unverged_eye(calibration.head, head, Eye::Right, palm)[2]);
                if (depth > 0.0) {
                    const auto [tl, tr] = verge_for_depth(depth);
                    vl = verge_velocity(Axis::VergeLeft, tl, head.verge_left_deg);
                    vr = verge_velocity(Axis::VergeRight, tr, head.verge_right_deg);
                }
            }
            command->values.set(Axis::VergeLeft, vl);
            command->values.set(Axis::VergeRight, vr);
        }
        submit(*command);
    }

    headctl::PointAim aim_for(const cv::Vec3d& target) const
    {
        const double margin = config.fixate.limit_margin_deg;
        auto [pan, tilt] = aim_at(target, calibration.head);
        return {target, clamp_to(axis_limits(Axis::Pan), pan, margin), clamp_to(axis_limits(Axis::Tilt), tilt, margin)};
    }

    // Pan and tilt to the aim, each eye looking at the target itself (both lines of sight
    // meet there).
    HeadCommand look_command(const headctl::PointAim& aim) const
    {
        HeadPose aimed;
        aimed.pan_deg = aim.pan_deg;
        aimed.tilt_deg = aim.tilt_deg;
        HeadCommand command{CommandKind::Absolute, {}};
        command.values.set(Axis::Pan, aim.pan_deg);
        command.values.set(Axis::Tilt, aim.tilt_deg);
        const Eye eyes[2] = {Eye::Left, Eye::Right};
        const Axis axes[2] = {Axis::VergeLeft, Axis::VergeRight};
        for (int i = 0; i < 2; ++i) {
            const cv::Vec3d q = in_unverged_eye(calibration.head, aimed, eyes[i], aim.target_mm);
            if (q[2] > 0.0)
                command.values.set(axes[i], clamp_to(axis_limits(axes[i]), std::atan2(q[0], q[2]) * kRadToDeg, 0.0));
        }
        return command;
    }

    HeadCommand return_command(const HeadPose& pose) const
    {
        HeadCommand command{CommandKind::Absolute, {}};
        command.values.set(Axis::Pan, clamp_to(axis_limits(Axis::Pan), pose.pan_deg, 0.0));
        command.values.set(Axis::Tilt, clamp_to(axis_limits(Axis::Tilt), pose.tilt_deg, 0.0));
        command.values.set(Axis::VergeLeft, clamp_to(axis_limits(Axis::VergeLeft), pose.verge_left_deg, 0.0));
        command.values.set(Axis::VergeRight, clamp_to(axis_limits(Axis::VergeRight), pose.verge_right_deg, 0.0));
        return command;
    }

    // Point mode's frame: feeds the dwell and carries out the director's step. True when
    // the fixate law steers this frame.
    bool steer_point(const FrameResult& r, double t_s, const HeadPose& head)
    {
        DwellParams params;
        params.dwell_s = config.times.dwell_s;
        params.release_s = config.times.dwell_s;
        params.target = config.target;
        const std::optional<cv::Vec3d> target = dwell.update(t_s, r.pointing, params);
        std::optional<headctl::PointAim> pick;
        if (target && dwell.picks() != dwell_picks) pick = aim_for(*target);
        dwell_picks = dwell.picks();
        const headctl::PointPhase before = director.phase();
        const headctl::PointStep step = director.update(t_s, pick, r.pointing.valid, r.left.valid(), head);
        char detail[160];
        switch (step.kind) {
        case headctl::PointStep::Kind::Follow:
            if (before != headctl::PointPhase::Following) {
                restart_fixate();
                report(SteeringEvent::Follow, "back where the hand was: following it again");
            }
            return true;
        case headctl::PointStep::Kind::Hold:
            return false;
        case headctl::PointStep::Kind::Aim:
            std::snprintf(detail, sizeof detail,
                          "a held pointing picked (%.0f, %.0f, %.0f) mm: looking there, pan %.1f tilt %.1f deg",
                          step.aim.target_mm[0], step.aim.target_mm[1], step.aim.target_mm[2], step.aim.pan_deg,
                          step.aim.tilt_deg);
            submit(look_command(step.aim));
            report(SteeringEvent::Look, detail);
            return false;
        case headctl::PointStep::Kind::Return:
            std::snprintf(detail, sizeof detail, "looked %.1f s: back to the hand at pan %.1f tilt %.1f deg",
                          config.times.look_s, step.pose.pan_deg, step.pose.tilt_deg);
            submit(return_command(step.pose));
            report(SteeringEvent::Return, detail);
            return false;
        }
        return false;
    }

    // Whether steering waits because someone else moved the head; starts and ends the pause.
    bool manual_pause(double t_s)
    {
        const std::optional<headctl::StateSample> latest = client->latest();
        if (config.times.manual_pause_s > 0.0 && latest &&
            watch.moved_by_someone_else(latest->state, to_seconds(latest->time))) {
            if (!paused_until_s) {
                char detail[120];
                std::snprintf(detail, sizeof detail, "the head was moved by someone else: steering pauses for %.1f s",
                              config.times.manual_pause_s);
                report(SteeringEvent::ManualPause, detail);
            }
            paused_until_s = t_s + config.times.manual_pause_s;  // from the last move seen
            watch.reset();
            still_sent = {};
        }
        if (!paused_until_s) return false;
        if (t_s < *paused_until_s) return true;
        paused_until_s.reset();
        restart_steering();
        report(SteeringEvent::Resume, "steering resumes from where the head is");
        return false;
    }

    void end_frame(const FrameResult& r)
    {
        remember_hand(r);
        if (!capture_time) return;
        view_age_ms = std::chrono::duration<double, std::milli>(client->now() - *capture_time).count();
        view_stale = view_age_ms > double(config.max_view_age.count());
        if (config.steer == SteerMode::Off) return;
        const std::optional<headctl::Timestamp> previous = steer_time;
        steer_time = capture_time;
        if (client->state() != headctl::ConnectionState::Connected || !capture_pose) {
            hand_direction.reset();
            return;  // a command would only wait in the slot and be stale when it is sent
        }
        refresh_limits();
        const double t_s = to_seconds(*capture_time);
        if (manual_pause(t_s)) return;
        static const FrameResult kNothingSeen{};
        const FrameResult& seen = view_stale ? kNothingSeen : r;
        const std::optional<headctl::StateSample> latest = client->latest();
        const HeadPose head = latest ? latest->state.pose : *capture_pose;
        if (config.steer == SteerMode::Point && !steer_point(seen, t_s, head)) return;
        if (!previous) return;
        const double dt = to_seconds(*capture_time - *previous);
        if (!(dt > 0.0) || dt > 10.0) {
            hand_direction.reset();
            return;
        }
        steer_fixate(seen, *capture_pose, head, dt);
    }
};

HeadLink::HeadLink(HeadLinkConfig config, StereoCalibration calibration)
{
    config.validate();
    impl_ = std::make_unique<Impl>(std::move(config), std::move(calibration));
}

HeadLink::~HeadLink() = default;

HeadAtCapture HeadLink::begin_frame(headctl::Timestamp capture_time)
{
    Impl& s = *impl_;
    HeadAtCapture out;
    out.pose = s.client->pose_at(capture_time);
    if (out.pose && s.capture_pose && s.capture_time && capture_time > *s.capture_time) {
        out.left_motion = s.motion_of(Eye::Left, *s.capture_pose, *out.pose);
        out.right_motion = s.motion_of(Eye::Right, *s.capture_pose, *out.pose);
    }
    s.capture_time = capture_time;
    s.capture_pose = out.pose;
    return out;
}

void HeadLink::end_frame(const FrameResult& result) { impl_->end_frame(result); }

void HeadLink::set_steering(SteerMode mode, const TargetPlacement& target)
{
    Impl& s = *impl_;
    check_target(target);
    s.config.target = target;
    if (mode == s.config.steer) return;
    s.config.steer = mode;
    s.steer_time.reset();
    s.paused_until_s.reset();
    s.refresh_limits();
    s.restart_steering();
    // Leaving a mode that was driving the head by velocity: stop it where it is.
    if (s.client->state() == headctl::ConnectionState::Connected) s.submit(HeadCommand{CommandKind::Stop, {}});
}

void HeadLink::set_times(const SteeringTimes& times)
{
    Impl& s = *impl_;
    if (times == s.config.times) return;
    times.validate();
    s.director.set_look_time(times.look_s);
    s.config.times = times;
    if (times.manual_pause_s == 0.0) s.paused_until_s.reset();
}

headctl::PointPhase HeadLink::point_phase() const { return impl_->director.phase(); }
bool HeadLink::paused() const { return impl_->paused_until_s.has_value(); }

bool HeadLink::last_view_stale() const { return impl_->view_stale; }
double HeadLink::last_view_age_ms() const { return impl_->view_age_ms; }

headctl::ConnectionState HeadLink::state() const { return impl_->client->state(); }
const headctl::HeadClient& HeadLink::client() const { return *impl_->client; }
headctl::Timestamp HeadLink::now() const { return impl_->client->now(); }
const HeadLinkConfig& HeadLink::config() const { return impl_->config; }

}  // namespace gc::headctl
