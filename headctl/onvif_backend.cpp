#include "headctl/onvif_backend.hpp"

#include <algorithm>

namespace gc::headctl {

namespace {

constexpr std::string_view kActionPrefix = "http://www.onvif.org/ver20/ptz/wsdl/";
constexpr double kSlack = 1e-9;

onvif::PtzRequest operation(std::string name)
{
    onvif::PtzRequest r;
    r.operation = std::move(name);
    return r;
}

void check_range(const char* what, double lo, double hi)
{
    if (!(lo < hi))
        throw std::invalid_argument(std::string("head URI: ") + what + " minimum must be below its maximum");
}

// A generic value within [lo, hi], or HeadRejected with `what` (the axis, the value and the
// assumed range).
double within(double generic, double lo, double hi, const std::string& what)
{
    if (generic < lo - kSlack || generic > hi + kSlack) throw HeadRejected(what);
    return std::clamp(generic, lo, hi);
}

std::string range_text(const char* axis, double value, double lo, double hi, const char* unit)
{
    char b[160];
    std::snprintf(b, sizeof b, "%s=%g%s is outside the range the URI assumes, [%g, %g]", axis, value, unit, lo, hi);
    return b;
}

}  // namespace

OnvifSettings OnvifSettings::from_uri(const HeadUri& uri)
{
    OnvifSettings s;
    s.user = uri.param("user").value_or("");
    s.profile = uri.param("profile").value_or(s.profile);
    s.pan_min_deg = uri.number_param("pan_min_deg", s.pan_min_deg, -360.0, 360.0);
    s.pan_max_deg = uri.number_param("pan_max_deg", s.pan_max_deg, -360.0, 360.0);
    s.tilt_min_deg = uri.number_param("tilt_min_deg", s.tilt_min_deg, -180.0, 180.0);
    s.tilt_max_deg = uri.number_param("tilt_max_deg", s.tilt_max_deg, -180.0, 180.0);
    check_range("pan", s.pan_min_deg, s.pan_max_deg);
    check_range("tilt", s.tilt_min_deg, s.tilt_max_deg);
    s.zoom_max = uri.number_param("zoom_max", s.zoom_max, 1.0, 1000.0);
    s.pan_max_speed_dps = uri.number_param("pan_max_speed_dps", s.pan_max_speed_dps, 0.1, 1000.0);
    s.tilt_max_speed_dps = uri.number_param("tilt_max_speed_dps", s.tilt_max_speed_dps, 0.1, 1000.0);
    s.zoom_max_speed = uri.number_param("zoom_max_speed", s.zoom_max_speed, 0.01, 1000.0);
    s.reply_timeout = std::chrono::milliseconds(
        static_cast<long>(uri.number_param("timeout_ms", static_cast<double>(s.reply_timeout.count()), 1, 60'000)));
    return s;
}

HeadLimits OnvifBackend::assumed_limits() const
{
    HeadLimits l = limits_with_zoom(*this, settings_.zoom_max, settings_.zoom_max_speed);
    l[Axis::Pan] = AxisLimits{settings_.pan_min_deg, settings_.pan_max_deg, settings_.pan_max_speed_dps};
    l[Axis::Tilt] = AxisLimits{settings_.tilt_min_deg, settings_.tilt_max_deg, settings_.tilt_max_speed_dps};
    return l;
}

OnvifBackend::OnvifBackend(std::string host, std::uint16_t port, std::string path, OnvifSettings settings,
                           std::string password)
    : host_(std::move(host)), port_(port), path_(path.empty() ? "/onvif/ptz_service" : std::move(path)),
      settings_(std::move(settings)), password_(std::move(password)),
      http_("http://" + (host_.find(':') != std::string::npos ? "[" + host_ + "]" : host_) + ":" +
            std::to_string(port_) + path_)
{
}

std::string OnvifBackend::name() const
{
    const bool v6 = host_.find(':') != std::string::npos;
    return "onvif://" + (v6 ? "[" + host_ + "]" : host_) + ":" + std::to_string(port_) + path_;
}

void OnvifBackend::open(Deadline deadline)
{
    close();
    query_state(deadline);  // reaches the camera and proves the credentials
}

void OnvifBackend::close()
{
    http_.reset();
    last_pose_.reset();
}

onvif::Envelope OnvifBackend::call(onvif::PtzRequest request, Deadline deadline)
{
    request.profile = settings_.profile;
    std::optional<onvif::UsernameToken> token;
    if (!settings_.user.empty()) token = onvif::make_username_token(settings_.user, password_);
    const auto limit = std::min(deadline, net::Clock::now() + settings_.reply_timeout);
    const HttpReply reply = http_.post(onvif::request_envelope(request, token),
                                       std::string(kActionPrefix) + request.operation, limit, onvif::kMaxMessageBytes);
    const std::string what = name() + " " + request.operation;
    onvif::Envelope envelope;
    try {
        envelope = onvif::parse_envelope(reply.body);
    } catch (const onvif::SoapError& e) {
        throw net::NetError(what + ": HTTP " + std::to_string(reply.status) + " without a SOAP reply (" + e.what() +
                            ")");
    }
    if (const auto f = onvif::fault(envelope)) {
        const std::string text = " (" + onvif::printable(f->subcode) + "): " + onvif::printable(f->reason);
        if (f->subcode == "NotAuthorized")
            throw net::NetError(name() + " refused the credentials" +
                                (settings_.user.empty() ? " (none given: add ?user=)" : " of user " + settings_.user) +
                                text);
        throw HeadRejected(what + " refused" + text);
    }
    if (reply.status != 200) throw net::NetError(what + ": HTTP " + std::to_string(reply.status));
    try {
        onvif::expect_response(envelope, request.operation);
    } catch (const onvif::SoapError& e) {
        throw net::NetError(what + ": " + onvif::printable(e.what()));
    }
    return envelope;
}

HeadState OnvifBackend::query_state(Deadline deadline)
{
    onvif::PtzStatus status;
    try {
        status = onvif::parse_status(call(operation("GetStatus"), deadline));
    } catch (const onvif::SoapError& e) {
        throw net::NetError(name() + " sent a malformed GetStatus reply: " + e.what());
    }
    HeadState s;
    const auto& c = settings_;
    set_axis_value(s.pose, Axis::Pan, onvif::from_generic(status.pan_tilt.x, c.pan_min_deg, c.pan_max_deg));
    set_axis_value(s.pose, Axis::Tilt, onvif::from_generic(status.pan_tilt.y, c.tilt_min_deg, c.tilt_max_deg));
    set_axis_value(s.pose, Axis::Zoom, has_zoom() ? onvif::zoom_from_generic(status.zoom, c.zoom_max) : 1.0);
    flag_motion_since(s, last_pose_);
    // One MoveStatus covers pan and tilt: where the positions show which of them moved, it
    // adds nothing (a pan would otherwise flag a tilt at rest, which steering then leaves
    // alone as perhaps someone else's move); where neither moved yet, it flags both.
    if (status.pan_tilt_moving && !s.moving_axis(Axis::Pan) && !s.moving_axis(Axis::Tilt)) {
        s.moving[static_cast<std::size_t>(Axis::Pan)] = true;
        s.moving[static_cast<std::size_t>(Axis::Tilt)] = true;
    }
    s.moving[static_cast<std::size_t>(Axis::Zoom)] |= status.zoom_moving;
    return s;
}

onvif::PanTilt OnvifBackend::generic_position(double pan, double tilt) const
{
    const auto& c = settings_;
    return {within(onvif::to_generic(pan, c.pan_min_deg, c.pan_max_deg), -1, 1,
                   range_text("pan", pan, c.pan_min_deg, c.pan_max_deg, " deg")),
            within(onvif::to_generic(tilt, c.tilt_min_deg, c.tilt_max_deg), -1, 1,
                   range_text("tilt", tilt, c.tilt_min_deg, c.tilt_max_deg, " deg"))};
}

void OnvifBackend::move_to(const AxisValues& target, Deadline deadline)
{
    onvif::PtzRequest r = operation("AbsoluteMove");
    if (target.has(Axis::Pan) || target.has(Axis::Tilt)) {
        // AbsoluteMove takes pan and tilt together: the axis not named stays where it is.
        double pan = target[Axis::Pan].value_or(0.0), tilt = target[Axis::Tilt].value_or(0.0);
        if (!target.has(Axis::Pan) || !target.has(Axis::Tilt)) {
            const HeadState now = query_state(deadline);
            pan = target[Axis::Pan].value_or(now.pose.pan_deg);
            tilt = target[Axis::Tilt].value_or(now.pose.tilt_deg);
        }
        r.pan_tilt = generic_position(pan, tilt);
    }
    if (target.has(Axis::Zoom)) {
        const double m = target.get(Axis::Zoom);
        r.zoom = within(onvif::zoom_to_generic(m, settings_.zoom_max), 0, 1,
                        range_text("zoom", m, 1.0, settings_.zoom_max, "x"));
    }
    call(r, deadline);
}

void OnvifBackend::drive(const AxisValues& velocity, Deadline deadline)
{
    const auto& c = settings_;
    const auto fraction = [&](Axis a, double max, const char* axis) {
        const double v = velocity[a].value_or(0.0);
        return within(v / max, -1, 1, range_text(axis, v, -max, max, " per s"));
    };
    onvif::PtzRequest r = operation("ContinuousMove");
    if (velocity.has(Axis::Pan) || velocity.has(Axis::Tilt))
        r.pan_tilt = onvif::PanTilt{fraction(Axis::Pan, c.pan_max_speed_dps, "pan"),
                                    fraction(Axis::Tilt, c.tilt_max_speed_dps, "tilt")};
    if (velocity.has(Axis::Zoom)) r.zoom = fraction(Axis::Zoom, c.zoom_max_speed, "zoom");
    call(r, deadline);
}

void OnvifBackend::send(const HeadCommand& command, Deadline deadline)
{
    switch (command.kind) {
    case CommandKind::Absolute:
        return move_to(command.values, deadline);
    case CommandKind::Relative: {
        const HeadState now = query_state(deadline);
        AxisValues target;
        for (Axis a : kAllAxes)
            if (command.values.has(a)) target.set(a, axis_value(now.pose, a) + command.values.get(a));
        return move_to(target, deadline);
    }
    case CommandKind::Velocity:
        return drive(command.values, deadline);
    case CommandKind::Stop:
        call(operation("Stop"), deadline);
        return;
    case CommandKind::Home:
        call(operation("GotoHomePosition"), deadline);
        return;
    case CommandKind::SavePreset: {
        onvif::PtzRequest r = operation("SetPreset");
        r.preset_token = std::to_string(command.preset);
        call(r, deadline);
        return;
    }
    case CommandKind::RecallPreset: {
        onvif::PtzRequest r = operation("GotoPreset");
        r.preset_token = std::to_string(command.preset);
        call(r, deadline);
        return;
    }
    }
}

std::vector<onvif::Preset> OnvifBackend::presets(Deadline deadline)
{
    try {
        return onvif::parse_presets(call(operation("GetPresets"), deadline));
    } catch (const onvif::SoapError& e) {
        throw net::NetError(name() + " sent a malformed GetPresets reply: " + e.what());
    }
}

}  // namespace gc::headctl
