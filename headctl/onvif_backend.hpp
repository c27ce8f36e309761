// A network camera's PTZ service over ONVIF (Profile S, SOAP 1.2 over HTTP) with a
// WS-Security UsernameToken digest when a user is given. Pan and tilt map linearly onto
// ONVIF's generic space -1..1 over an assumed range in degrees, zoom onto 0..1 from 1x to
// zoom_max; the URI's query sets them (docs/head-protocol.md).
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/onvif_soap.hpp"
#include "headctl/soap_http.hpp"

#include <chrono>
#include <vector>

namespace gc::headctl {

struct OnvifSettings {
    std::string user;  // empty: no UsernameToken
    std::string profile = "profile_1";
    double pan_min_deg = -170.0;  // what generic x = -1 and +1 mean
    double pan_max_deg = 170.0;
    double tilt_min_deg = -45.0;
    double tilt_max_deg = 45.0;
    double zoom_max = 20.0;            // magnification at zoom x = 1 (1: no zoom axis)
    double pan_max_speed_dps = 120.0;  // what a generic velocity of 1 means
    double tilt_max_speed_dps = 90.0;
    double zoom_max_speed = 8.0;  // magnification per second
    std::chrono::milliseconds reply_timeout{1000};

    static OnvifSettings from_uri(const HeadUri& uri);  // throws std::invalid_argument
};

class OnvifBackend final : public HeadBackend {
public:
    // `path` is the PTZ service's path (default /onvif/ptz_service); `password` goes only
    // into digests.
    OnvifBackend(std::string host, std::uint16_t port, std::string path, OnvifSettings settings, std::string password);

    void open(Deadline deadline) override;
    void close() override;
    HeadState query_state(Deadline deadline) override;
    void send(const HeadCommand& command, Deadline deadline) override;
    std::optional<HeadLimits> query_limits(Deadline) override { return std::nullopt; }
    HeadLimits assumed_limits() const override;
    std::array<bool, kAxisCount> axes() const override { return {true, true, false, false, has_zoom()}; }
    std::string name() const override;

    std::vector<onvif::Preset> presets(Deadline deadline);

private:
    // Sends one request and returns the response's envelope: net::NetError when the camera
    // cannot be reached, answers garbage or refuses the credentials; HeadRejected for other faults.
    onvif::Envelope call(onvif::PtzRequest request, Deadline deadline);
    bool has_zoom() const { return settings_.zoom_max > 1.0; }
    onvif::PanTilt generic_position(double pan_deg, double tilt_deg) const;
    void move_to(const AxisValues& target, Deadline deadline);
    void drive(const AxisValues& velocity, Deadline deadline);

    std::string host_;
    std::uint16_t port_;
    std::string path_;
    OnvifSettings settings_;
    std::string password_;
    SoapHttpClient http_;
    std::optional<HeadPose> last_pose_;
};

}  // namespace gc::headctl
