// A PTZ camera's pan-tilt head over VISCA: VISCA over IP (UDP, 8-byte header with sequence
// numbers), raw VISCA over a TCP stream, or over a serial line. Pan, tilt and (when the URI says how far the lens
// magnifies) zoom.
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/visca.hpp"

#include <chrono>

namespace gc::headctl {

// How degrees map onto a camera's units; from the URI's query (docs/head-protocol.md).
struct ViscaSettings {
    int address = 1;
    double pan_units_per_deg = 16.0;  // a negative scale flips the axis
    double tilt_units_per_deg = 16.0;
    double pan_max_speed_dps = 100.0;  // the speed of drive code 0x18
    double tilt_max_speed_dps = 90.0;  // the speed of drive code 0x14
    // The lens: magnification at the tele end (1: no zoom axis), its VISCA position, and the
    // speed (magnification per second) of zoom drive code 7. Positions between are taken as
    // linear in magnification.
    double zoom_max = 1.0;
    int zoom_tele_units = 0x4000;
    double zoom_max_speed = 8.0;
    std::chrono::milliseconds reply_timeout{500};
    int baud = 9600;  // Serial

    static ViscaSettings from_uri(const HeadUri& uri);  // throws std::invalid_argument
};

class ViscaBackend final : public HeadBackend {
public:
    // Serial: `host` is the device path; raw VISCA as over TCP.
    enum class Transport { Udp, Tcp, Serial };
    ViscaBackend(std::string host, std::uint16_t port, Transport transport, ViscaSettings settings);

    void open(Deadline deadline) override;
    void close() override;
    HeadState query_state(Deadline deadline) override;
    void send(const HeadCommand& command, Deadline deadline) override;
    std::optional<HeadLimits> query_limits(Deadline) override { return std::nullopt; }
    HeadLimits assumed_limits() const override
    {
        return limits_with_zoom(*this, settings_.zoom_max, settings_.zoom_max_speed);
    }
    std::array<bool, kAxisCount> axes() const override { return {true, true, false, false, has_zoom()}; }
    std::string name() const override;

private:
    // Sends one VISCA message and waits for its reply: `answer` is Ack for a command (a
    // completion also does over UDP), the kind of position reply for an inquiry.
    visca::Reply exchange(const visca::Bytes& message, visca::ReplyKind answer, Deadline deadline);
    std::optional<visca::Bytes> receive_message(Deadline deadline, std::uint32_t expected_sequence);
    int to_units(double deg, double units_per_deg, const char* axis) const;
    int speed_code(double dps, double max_dps, int max_code) const;
    bool has_zoom() const { return settings_.zoom_max > 1.0; }
    int zoom_units(double magnification) const;
    double zoom_magnification(int units) const;
    void send_pan_tilt(const HeadCommand& command, Deadline deadline);
    void send_zoom(const HeadCommand& command, Deadline deadline);

    std::string host_;
    std::uint16_t port_;
    Transport transport_;
    ViscaSettings settings_;
    net::Fd fd_;
    std::uint32_t sequence_ = 0;
    visca::Bytes stream_;                // TCP: bytes of the unfinished message
    std::array<double, 2> drive_dps_{};  // last velocity per axis, so one-axis drives keep the other
    std::optional<HeadPose> last_pose_;
};

}  // namespace gc::headctl
