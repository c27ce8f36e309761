#include "headctl/head_backend.hpp"

#include "headctl/gchp_backend.hpp"
#include "headctl/onvif_backend.hpp"
#include "headctl/pelco_backend.hpp"
#include "headctl/visca_backend.hpp"

#include <cstdio>

namespace gc::headctl {

HeadLimits HeadBackend::assumed_limits() const
{
    HeadLimits l;
    l[Axis::Pan].min_deg = -180.0;
    l[Axis::Pan].max_deg = 180.0;
    return l;
}

// For backends that know only their lens: the default range with zoom up to `zoom_max`.
HeadLimits limits_with_zoom(const HeadBackend& backend, double zoom_max, double zoom_speed)
{
    HeadLimits l = backend.HeadBackend::assumed_limits();
    l[Axis::Zoom] = AxisLimits{1.0, zoom_max, zoom_speed, 4.0 * zoom_speed};  // full speed within 0.25 s
    return l;
}

std::string describe(const HeadCommand& c)
{
    std::string out;
    switch (c.kind) {
    case CommandKind::Absolute:
        out = "move abs";
        break;
    case CommandKind::Relative:
        out = "move rel";
        break;
    case CommandKind::Velocity:
        out = "move vel";
        break;
    case CommandKind::Stop:
        return "stop";
    case CommandKind::Home:
        return "home";
    case CommandKind::SavePreset:
        return "preset save " + std::to_string(c.preset);
    case CommandKind::RecallPreset:
        return "preset recall " + std::to_string(c.preset);
    }
    for (Axis a : kAllAxes) {
        if (!c.values.has(a)) continue;
        char b[48];
        std::snprintf(b, sizeof b, " %s=%g", std::string(axis_name(a)).c_str(), c.values.get(a));
        out += b;
    }
    return out;
}

void flag_motion_since(HeadState& s, std::optional<HeadPose>& last)
{
    if (last)
        for (Axis a : kAllAxes) s.moving[static_cast<std::size_t>(a)] = axis_value(s.pose, a) != axis_value(*last, a);
    last = s.pose;
}

std::unique_ptr<HeadBackend> make_backend(const HeadUri& uri, const std::string& token)
{
    switch (uri.scheme) {
    case HeadScheme::Gchp:
        return std::make_unique<GchpBackend>(uri.host, uri.port,
                                             token.empty() ? uri.param("token").value_or("") : token);
    case HeadScheme::ViscaUdp:
        return std::make_unique<ViscaBackend>(uri.host, uri.port, ViscaBackend::Transport::Udp,
                                              ViscaSettings::from_uri(uri));
    case HeadScheme::PelcoD:
        return std::make_unique<PelcoBackend>(uri.path, PelcoSettings::from_uri(uri));
    case HeadScheme::ViscaSerial:
        return std::make_unique<ViscaBackend>(uri.path, 0, ViscaBackend::Transport::Serial,
                                              ViscaSettings::from_uri(uri));
    case HeadScheme::ViscaTcp:
        return std::make_unique<ViscaBackend>(uri.host, uri.port, ViscaBackend::Transport::Tcp,
                                              ViscaSettings::from_uri(uri));
    case HeadScheme::Onvif:
        return std::make_unique<OnvifBackend>(uri.host, uri.port, uri.path, OnvifSettings::from_uri(uri),
                                              token.empty() ? uri.param("token").value_or("") : token);
    }
    throw std::invalid_argument("unknown head URI scheme");
}

}  // namespace gc::headctl
