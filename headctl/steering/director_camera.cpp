#include "headctl/steering/director_camera.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc::headctl {

std::string_view to_string(DirectorEvent event)
{
    switch (event) {
    case DirectorEvent::Frame:
        return "frame";
    case DirectorEvent::Home:
        return "home";
    case DirectorEvent::ManualPause:
        return "manual-pause";
    case DirectorEvent::Resume:
        return "resume";
    }
    return "unknown";
}

namespace {

void check_region(double region_mm)
{
    if (!std::isfinite(region_mm) || region_mm <= 0.0) throw std::invalid_argument("director: region_mm must be > 0");
}

void check_manual_pause(double seconds)
{
    if (!std::isfinite(seconds) || seconds < 0.0) throw std::invalid_argument("director: manual_pause_s must be >= 0");
}

}  // namespace

void DirectorCameraConfig::validate() const
{
    check_region(region_mm);
    if (home_preset && (*home_preset < 0 || *home_preset > kMaxPreset))
        throw std::invalid_argument("director: home_preset must be 0.." + std::to_string(kMaxPreset));
    if (mount.image_size.width <= 0 || mount.image_size.height <= 0 || !(mount.K(0, 0) > 0.0))
        throw std::invalid_argument("director: the mount needs an image size and a focal length");
    check_manual_pause(manual_pause_s);
}

struct DirectorCamera::Impl {
    DirectorCameraConfig config;
    std::unique_ptr<HeadClient> client;
    std::optional<cv::Vec3d> framed;  // the target last sent
    std::optional<HeadPose> aim;
    bool away_from_home = false;  // a target was framed since the camera was last sent home
    // For cameras that do not report their range (VISCA, Pelco-D, ONVIF): the range their
    // backends work within (the URI's zoom_max, an ONVIF pan and tilt range).
    HeadLimits unreported;
    ManualMoveWatch watch;
    std::optional<double> paused_until_s;

    explicit Impl(DirectorCameraConfig c) : config(std::move(c)), watch(config.manual)
    {
        config.validate();
        unreported = make_backend(parse_head_uri(config.uri), config.token)->assumed_limits();
        HeadClientConfig cc;
        cc.uri = config.uri;
        cc.token = config.token;
        cc.clock = config.clock;
        cc.on_state_change = config.on_state_change;
        client = std::make_unique<HeadClient>(std::move(cc));
    }

    void submit(const HeadCommand& command)
    {
        client->submit(command);
        watch.commanded(command, to_seconds(client->now()));
        if (config.on_command) config.on_command(command);
    }

    // Starts, extends and ends the pause after someone else moved the camera.
    std::optional<DirectorEvent> manual_pause()
    {
        const std::optional<StateSample> latest = client->latest();
        const double now_s = to_seconds(client->now());
        std::optional<DirectorEvent> event;
        if (config.manual_pause_s > 0.0 && latest &&
            watch.moved_by_someone_else(latest->state, to_seconds(latest->time))) {
            if (!paused_until_s) event = DirectorEvent::ManualPause;
            paused_until_s = now_s + config.manual_pause_s;  // from the last move seen
            watch.reset();
        }
        if (paused_until_s && now_s >= *paused_until_s) {
            // From where the person left it: a target still held is framed anew, a released
            // one does not send it home.
            paused_until_s.reset();
            framed.reset();
            aim.reset();
            away_from_home = false;
            event = DirectorEvent::Resume;
        }
        return event;
    }

    // Pan, tilt and, on a camera with a zoom lens, zoom; false until the camera has answered
    // (a zoom beyond its range would be refused).
    bool frame(const cv::Vec3d& target)
    {
        std::optional<HeadLimits> limits = client->limits();
        if (!limits && client->state() == ConnectionState::Connected) limits = unreported;
        if (!limits) return false;
        const AxisLimits& zoom = (*limits)[Axis::Zoom];
        const HeadPose pose = director_aim(config.mount, target, config.region_mm, zoom.min_deg, zoom.max_deg);
        HeadCommand command{CommandKind::Absolute, {}, 0};
        command.values.set(Axis::Pan,
                           std::clamp(pose.pan_deg, (*limits)[Axis::Pan].min_deg, (*limits)[Axis::Pan].max_deg));
        command.values.set(Axis::Tilt,
                           std::clamp(pose.tilt_deg, (*limits)[Axis::Tilt].min_deg, (*limits)[Axis::Tilt].max_deg));
        if (client->has_axis(Axis::Zoom)) command.values.set(Axis::Zoom, pose.zoom);
        submit(command);
        aim = pose;
        return true;
    }

    void go_home()
    {
        submit(config.home_preset ? preset_command(CommandKind::RecallPreset, *config.home_preset)
                                  : HeadCommand{CommandKind::Home, {}, 0});
        aim.reset();
    }
};

DirectorCamera::DirectorCamera(DirectorCameraConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
DirectorCamera::~DirectorCamera() = default;

std::optional<DirectorEvent> DirectorCamera::show(const std::optional<cv::Vec3d>& target)
{
    Impl& s = *impl_;
    const std::optional<DirectorEvent> pause = s.manual_pause();
    if (s.paused_until_s || pause == DirectorEvent::Resume) return pause;
    if (target) {
        const bool same = s.framed && cv::norm(*target - *s.framed) <= 1.0;
        if (same || !s.frame(*target)) return pause;
        s.framed = target;
        s.away_from_home = true;
        return DirectorEvent::Frame;
    }
    s.framed.reset();
    if (!s.away_from_home) return pause;
    s.go_home();
    s.away_from_home = false;
    return DirectorEvent::Home;
}

void DirectorCamera::set_region(double region_mm)
{
    check_region(region_mm);
    impl_->config.region_mm = region_mm;
}

void DirectorCamera::set_manual_pause(double seconds)
{
    check_manual_pause(seconds);
    impl_->config.manual_pause_s = seconds;
    if (seconds == 0.0 && impl_->paused_until_s) impl_->paused_until_s = -1.0;  // ends at the next show()
}

std::optional<HeadPose> DirectorCamera::aim() const { return impl_->aim; }
bool DirectorCamera::paused() const { return impl_->paused_until_s.has_value(); }
const HeadClient& DirectorCamera::client() const { return *impl_->client; }

}  // namespace gc::headctl
