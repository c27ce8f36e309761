#include "headctl/visca_backend.hpp"

#include "headctl/serial_port.hpp"

#include <algorithm>
#include <cmath>

namespace gc::headctl {

namespace {
constexpr int kMaxRepliesPerExchange = 16;
}

ViscaSettings ViscaSettings::from_uri(const HeadUri& uri)
{
    ViscaSettings s;
    s.address = address_param(uri, 7);
    s.pan_units_per_deg = uri.number_param("pan_units_per_deg", s.pan_units_per_deg, -1000.0, 1000.0);
    s.tilt_units_per_deg = uri.number_param("tilt_units_per_deg", s.tilt_units_per_deg, -1000.0, 1000.0);
    if (std::abs(s.pan_units_per_deg) < 1e-3 || std::abs(s.tilt_units_per_deg) < 1e-3)
        throw std::invalid_argument("head URI: a units-per-degree scale must not be 0");
    s.pan_max_speed_dps = uri.number_param("pan_max_speed_dps", s.pan_max_speed_dps, 0.1, 1000.0);
    s.tilt_max_speed_dps = uri.number_param("tilt_max_speed_dps", s.tilt_max_speed_dps, 0.1, 1000.0);
    s.zoom_max = uri.number_param("zoom_max", s.zoom_max, 1.0, 1000.0);
    const double tele = uri.number_param("zoom_tele_units", s.zoom_tele_units, 1, 0xFFFF);
    if (tele != std::floor(tele)) throw std::invalid_argument("head URI: parameter zoom_tele_units must be an integer");
    s.zoom_tele_units = static_cast<int>(tele);
    s.zoom_max_speed = uri.number_param("zoom_max_speed", s.zoom_max_speed, 0.01, 1000.0);
    s.baud = baud_param(uri, s.baud);
    s.reply_timeout = reply_timeout_param(uri, s.reply_timeout);
    return s;
}

ViscaBackend::ViscaBackend(std::string host, std::uint16_t port, Transport transport, ViscaSettings settings)
    : host_(std::move(host)), port_(port), transport_(transport), settings_(settings)
{
}

std::string ViscaBackend::name() const
{
    if (transport_ == Transport::Serial) return "visca-serial://" + host_;
    return std::string(transport_ == Transport::Udp ? "visca-udp://" : "visca-tcp://") + host_ + ":" +
           std::to_string(port_);
}

void ViscaBackend::open(Deadline deadline)
{
    close();
    if (transport_ == Transport::Serial) {
        fd_ = open_serial_port(host_, settings_.baud);
        return;
    }
    fd_ = net::connect_to(host_, port_, transport_ == Transport::Udp ? net::Transport::Udp : net::Transport::Tcp,
                          deadline);
    if (transport_ == Transport::Tcp) return;
    // UDP has no connection: the sequence reset doubles as the check that a camera answers.
    const visca::Bytes reset = visca::ip_reset_sequence(0);
    net::send_all(fd_.get(), std::span<const std::uint8_t>(reset), deadline);
    std::array<std::uint8_t, 64> buffer{};
    for (int i = 0; i < kMaxRepliesPerExchange; ++i) {
        const auto n = net::receive_some(fd_.get(), buffer, deadline);
        if (!n) throw net::NetError(name() + " did not acknowledge the sequence reset");
        try {
            const auto m = visca::unwrap_ip(std::span<const std::uint8_t>(buffer.data(), *n));
            if (m.payload_type == visca::kIpControlReply) {
                sequence_ = 0;
                return;
            }
        } catch (const visca::ViscaError&) {
            // not ours: keep waiting
        }
    }
    throw net::NetError(name() + " did not acknowledge the sequence reset");
}

void ViscaBackend::close()
{
    fd_.reset();
    stream_.clear();
    last_pose_.reset();
    drive_dps_ = {};
}

std::optional<visca::Bytes> ViscaBackend::receive_message(Deadline deadline, std::uint32_t expected_sequence)
{
    std::array<std::uint8_t, 512> buffer{};
    for (;;) {
        if (transport_ != Transport::Udp) {  // a byte stream
            const auto end = std::find(stream_.begin(), stream_.end(), 0xFF);
            if (end != stream_.end()) {
                visca::Bytes message(stream_.begin(), end + 1);
                stream_.erase(stream_.begin(), end + 1);
                return message;
            }
            if (stream_.size() >= visca::kMaxMessageSize) throw net::NetError(name() + " sent an unterminated message");
        }
        const auto n = net::receive_some(fd_.get(), buffer, deadline);
        if (!n) return std::nullopt;
        const std::span<const std::uint8_t> got(buffer.data(), *n);
        if (transport_ != Transport::Udp) {
            stream_.insert(stream_.end(), got.begin(), got.end());
            continue;
        }
        try {
            auto m = visca::unwrap_ip(got);
            if (m.payload_type == visca::kIpReply && m.sequence == expected_sequence) return m.payload;
        } catch (const visca::ViscaError&) {
            // a malformed datagram is skipped like one that is not ours
        }
        // Datagrams that are not the reply may keep coming faster than they are read: the
        // deadline is looked at after each, not only when none waits.
        if (net::Clock::now() >= deadline) return std::nullopt;
    }
}

visca::Reply ViscaBackend::exchange(const visca::Bytes& message, visca::ReplyKind answer, Deadline deadline)
{
    if (!fd_) throw net::NetError("not connected");
    const bool inquiry = answer != visca::ReplyKind::Ack;
    const std::uint32_t seq = sequence_++;
    if (transport_ == Transport::Udp) {
        const auto datagram = visca::wrap_ip(inquiry ? visca::kIpInquiry : visca::kIpCommand, seq, message);
        net::send_all(fd_.get(), std::span<const std::uint8_t>(datagram), deadline);
    } else {
        net::send_all(fd_.get(), std::span<const std::uint8_t>(message), deadline);
    }
    const Deadline reply_deadline = std::min(deadline, net::Clock::now() + settings_.reply_timeout);
    for (int i = 0; i < kMaxRepliesPerExchange; ++i) {
        const auto bytes = receive_message(reply_deadline, seq);
        if (!bytes) throw net::NetError(name() + " did not answer in time");
        visca::Reply r;
        try {
            r = visca::parse_reply(*bytes);
        } catch (const visca::ViscaError& e) {
            throw net::NetError(name() + ": " + e.what());
        }
        if (r.kind == visca::ReplyKind::Error)
            throw HeadRejected(name() + " refused: " + visca::describe_error(r.error));
        if (inquiry && r.kind == answer) return r;
        // A completion may belong to an earlier command; a command is accepted on its ACK.
        if (!inquiry && r.kind == visca::ReplyKind::Ack) return r;
        if (!inquiry && r.kind == visca::ReplyKind::Completion && transport_ == Transport::Udp) return r;
    }
    throw net::NetError(name() + " sent too many unrelated replies");
}

int ViscaBackend::to_units(double deg, double units_per_deg, const char* axis) const
{
    const double units = std::round(deg * units_per_deg);
    if (!std::isfinite(units) || std::abs(units) > 0x7FFF)
        throw HeadRejected(std::string(axis) + " " + std::to_string(deg) + " deg is beyond the VISCA range");
    return static_cast<int>(units);
}

int ViscaBackend::speed_code(double dps, double max_dps, int max_code) const
{
    return std::clamp(static_cast<int>(std::lround(std::abs(dps) / max_dps * max_code)), 1, max_code);
}

HeadState ViscaBackend::query_state(Deadline deadline)
{
    const auto r = exchange(visca::pan_tilt_position_inquiry(settings_.address), visca::ReplyKind::Position, deadline);
    HeadState s;
    s.pose.pan_deg = r.pan_units / settings_.pan_units_per_deg;
    s.pose.tilt_deg = r.tilt_units / settings_.tilt_units_per_deg;
    if (has_zoom())
        s.pose.zoom = zoom_magnification(
            exchange(visca::zoom_position_inquiry(settings_.address), visca::ReplyKind::ZoomPosition, deadline)
                .zoom_units);
    // VISCA reports no motion flags: an axis moves if it changed since the last inquiry.
    flag_motion_since(s, last_pose_);
    return s;
}

int ViscaBackend::zoom_units(double magnification) const
{
    if (!(magnification >= 1.0 && magnification <= settings_.zoom_max))
        throw HeadRejected(name() + ": zoom " + std::to_string(magnification) + " is outside [1, " +
                           std::to_string(settings_.zoom_max) + "]");
    return static_cast<int>(
        std::lround(visca::zoom_to_units(magnification, 1.0, settings_.zoom_max, settings_.zoom_tele_units)));
}

double ViscaBackend::zoom_magnification(int units) const
{
    return visca::zoom_from_units(std::clamp(units, 0, settings_.zoom_tele_units), 1.0, settings_.zoom_max,
                                  settings_.zoom_tele_units);
}

void ViscaBackend::send(const HeadCommand& c, Deadline deadline)
{
    if (c.values.has(Axis::VergeLeft) || c.values.has(Axis::VergeRight))
        throw HeadRejected(name() + " has no vergence axes");
    if (c.values.has(Axis::Zoom) && !has_zoom())
        throw HeadRejected(name() + " has no zoom axis (the URI's zoom_max is 1)");
    if (is_preset(c.kind)) {
        if (c.preset < 0 || c.preset > 0x7F)
            throw HeadRejected(name() + ": preset " + std::to_string(c.preset) + " is not in 0..127");
        const auto action = c.kind == CommandKind::SavePreset ? visca::MemoryAction::Set : visca::MemoryAction::Recall;
        exchange(visca::memory(settings_.address, action, c.preset), visca::ReplyKind::Ack, deadline);
        return;
    }
    const bool pan_tilt = c.values.has(Axis::Pan) || c.values.has(Axis::Tilt);
    const bool all = c.kind == CommandKind::Home || c.kind == CommandKind::Stop;
    if (pan_tilt || all) send_pan_tilt(c, deadline);
    if (has_zoom() && (c.values.has(Axis::Zoom) || all)) send_zoom(c, deadline);
}

// The lens is a separate VISCA device (CAM_Zoom): its own messages after the pan-tilt one.
void ViscaBackend::send_zoom(const HeadCommand& c, Deadline deadline)
{
    const int a = settings_.address;
    switch (c.kind) {
    case CommandKind::Home:
        exchange(visca::zoom_direct(a, 0), visca::ReplyKind::Ack, deadline);
        return;
    case CommandKind::Stop:
        exchange(visca::zoom_drive(a, 0, visca::Direction::Stop), visca::ReplyKind::Ack, deadline);
        return;
    case CommandKind::Absolute:
        exchange(visca::zoom_direct(a, zoom_units(c.values.get(Axis::Zoom))), visca::ReplyKind::Ack, deadline);
        return;
    case CommandKind::Relative: {
        const double here = last_pose_ ? last_pose_->zoom : query_state(deadline).pose.zoom;
        exchange(visca::zoom_direct(a, zoom_units(here + c.values.get(Axis::Zoom))), visca::ReplyKind::Ack, deadline);
        return;
    }
    case CommandKind::Velocity: {
        const double v = c.values.get(Axis::Zoom);
        const auto direction = std::abs(v) < 1e-6 ? visca::Direction::Stop
                               : v > 0            ? visca::Direction::Positive
                                                  : visca::Direction::Negative;
        // Zoom speed codes start at 0 (the slowest), unlike pan and tilt.
        const int code =
            std::clamp(static_cast<int>(std::lround(std::abs(v) / settings_.zoom_max_speed * visca::kMaxZoomSpeed)), 0,
                       visca::kMaxZoomSpeed);
        exchange(visca::zoom_drive(a, code, direction), visca::ReplyKind::Ack, deadline);
        return;
    }
    case CommandKind::SavePreset:
    case CommandKind::RecallPreset:
        return;  // sent by send()
    }
}

void ViscaBackend::send_pan_tilt(const HeadCommand& c, Deadline deadline)
{
    // Position moves run at the fastest speed codes; the camera's own profile shapes them.
    const int pan_max = visca::kMaxPanSpeed;
    const int tilt_max = visca::kMaxTiltSpeed;
    const int a = settings_.address;
    switch (c.kind) {
    case CommandKind::SavePreset:
    case CommandKind::RecallPreset:
        return;  // sent by send()
    case CommandKind::Home:
        drive_dps_ = {};
        exchange(visca::pan_tilt_home(a), visca::ReplyKind::Ack, deadline);
        return;
    case CommandKind::Stop:
        drive_dps_ = {};
        exchange(visca::pan_tilt_stop(a), visca::ReplyKind::Ack, deadline);
        return;
    case CommandKind::Absolute:
    case CommandKind::Relative: {
        // One message moves both axes: an axis not named stays where it is (moves by 0).
        const bool absolute = c.kind == CommandKind::Absolute;
        HeadPose from;
        if (absolute) from = last_pose_ ? *last_pose_ : query_state(deadline).pose;
        const double pan = c.values.has(Axis::Pan) ? c.values.get(Axis::Pan) : from.pan_deg;
        const double tilt = c.values.has(Axis::Tilt) ? c.values.get(Axis::Tilt) : from.tilt_deg;
        const auto move = absolute ? visca::pan_tilt_absolute : visca::pan_tilt_relative;
        drive_dps_ = {};
        exchange(move(a, pan_max, tilt_max, to_units(pan, settings_.pan_units_per_deg, "pan"),
                      to_units(tilt, settings_.tilt_units_per_deg, "tilt")),
                 visca::ReplyKind::Ack, deadline);
        return;
    }
    case CommandKind::Velocity: {
        if (c.values.has(Axis::Pan)) drive_dps_[0] = c.values.get(Axis::Pan);
        if (c.values.has(Axis::Tilt)) drive_dps_[1] = c.values.get(Axis::Tilt);
        // Direction in camera terms: the sign of the unit scale says which way is positive.
        auto direction = [](double dps, double scale) {
            const double v = dps * scale;
            if (std::abs(dps) < 1e-6) return visca::Direction::Stop;
            return v > 0 ? visca::Direction::Positive : visca::Direction::Negative;
        };
        exchange(visca::pan_tilt_drive(a, speed_code(drive_dps_[0], settings_.pan_max_speed_dps, visca::kMaxPanSpeed),
                                       speed_code(drive_dps_[1], settings_.tilt_max_speed_dps, visca::kMaxTiltSpeed),
                                       direction(drive_dps_[0], settings_.pan_units_per_deg),
                                       direction(drive_dps_[1], settings_.tilt_units_per_deg)),
                 visca::ReplyKind::Ack, deadline);
        return;
    }
    }
}

}  // namespace gc::headctl
