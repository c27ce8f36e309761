#include "headctl/sim/visca_responder.hpp"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace gc::headctl {

namespace {

constexpr int kCommandSocket = 1;  // the socket a command's ACK and completion name
constexpr int kMessageLengthError = 0x01;
constexpr int kSyntaxError = 0x02;
constexpr int kNotExecutable = 0x41;
constexpr int kPollMs = 50;  // how soon the thread sees a stop request
constexpr std::size_t kMaxStreams = 4;

double sign(visca::Direction d) { return static_cast<double>(static_cast<int>(d)); }

int clamp_units(double v, int lo, int hi) { return static_cast<int>(std::clamp(std::lround(v), long{lo}, long{hi})); }

// The lens position of a magnification and back: linear from the widest (0) to the largest.
double zoom_of(int units, const HeadLimits& l, const ViscaUnits& u)
{
    const AxisLimits& z = l[Axis::Zoom];
    return visca::zoom_from_units(units, z.min_deg, z.max_deg, u.zoom_tele_units);
}

int units_of_zoom(double zoom, const HeadLimits& l, const ViscaUnits& u)
{
    const AxisLimits& z = l[Axis::Zoom];
    if (z.max_deg <= z.min_deg) return 0;
    return clamp_units(visca::zoom_to_units(zoom, z.min_deg, z.max_deg, u.zoom_tele_units), 0, 0xFFFF);
}

AxisValues pan_tilt(double pan_deg, double tilt_deg)
{
    AxisValues v;
    v.set(Axis::Pan, pan_deg);
    v.set(Axis::Tilt, tilt_deg);
    return v;
}

// A drive's speed codes as velocities: the fastest code is the axis's top speed.
AxisValues drive_velocities(const visca::Message& m, const HeadLimits& l)
{
    return pan_tilt(sign(m.pan) * m.pan_speed / visca::kMaxPanSpeed * l[Axis::Pan].max_velocity_dps,
                    sign(m.tilt) * m.tilt_speed / visca::kMaxTiltSpeed * l[Axis::Tilt].max_velocity_dps);
}

// The zoom's speed code as a velocity: code 0 is the slowest, half of code 1's speed.
AxisValues zoom_velocity(const visca::Message& m, const HeadLimits& l)
{
    AxisValues v;
    const double code = std::max(0.5, static_cast<double>(m.zoom_speed));
    v.set(Axis::Zoom, sign(m.zoom) * code / visca::kMaxZoomSpeed * l[Axis::Zoom].max_velocity_dps);
    return v;
}

// Carries out one command on the head; throws std::out_of_range when the head refuses it.
void carry_out(HeadModel& model, double now, const visca::Message& m, const ViscaUnits& u)
{
    const HeadLimits& l = model.limits();
    using visca::MessageKind;
    switch (m.kind) {
    case MessageKind::Drive:
        model.move_velocity(drive_velocities(m, l), now);
        return;
    case MessageKind::Absolute:
        model.move_absolute(pan_tilt(m.pan_units / u.units_per_deg, m.tilt_units / u.units_per_deg), now);
        return;
    case MessageKind::Relative:
        model.move_relative(pan_tilt(m.pan_units / u.units_per_deg, m.tilt_units / u.units_per_deg), now);
        return;
    case MessageKind::Home:
        model.move_absolute(pan_tilt(home_value(Axis::Pan), home_value(Axis::Tilt)), now);
        return;
    case MessageKind::ZoomDirect: {
        AxisValues v;
        v.set(Axis::Zoom, zoom_of(m.zoom_units, l, u));
        model.move_absolute(v, now);
        return;
    }
    case MessageKind::ZoomDrive:
        model.move_velocity(zoom_velocity(m, l), now);
        return;
    case MessageKind::Memory:
        if (m.memory_action == visca::MemoryAction::Set) model.save_preset(m.memory_number, now);
        if (m.memory_action == visca::MemoryAction::Recall) model.recall_preset(m.memory_number, now);
        if (m.memory_action == visca::MemoryAction::Reset) throw std::out_of_range("presets cannot be cleared");
        return;
    case MessageKind::PositionInquiry:
    case MessageKind::ZoomInquiry:
        return;  // answered by answer_visca
    }
}

visca::Bytes inquiry_reply(HeadModel& model, double now, const visca::Message& m, const ViscaUnits& u)
{
    const HeadPose pose = model.state(now).pose;
    if (m.kind == visca::MessageKind::ZoomInquiry)
        return visca::zoom_position_reply(m.address, units_of_zoom(pose.zoom, model.limits(), u));
    return visca::position_reply(m.address, clamp_units(pose.pan_deg * u.units_per_deg, -0x8000, 0x7FFF),
                                 clamp_units(pose.tilt_deg * u.units_per_deg, -0x8000, 0x7FFF));
}

}  // namespace

std::vector<visca::Bytes> answer_visca(HeadModel& model, double now, std::span<const std::uint8_t> bytes,
                                       const ViscaUnits& u)
{
    visca::Message m;
    try {
        m = visca::parse_message(bytes);
    } catch (const visca::ViscaError&) {
        // The error names the address the message was sent to, when it is one.
        const int to = !bytes.empty() && (bytes[0] >> 4) == 0x8 && (bytes[0] & 0x0F) >= 1 && (bytes[0] & 0x0F) <= 7
                           ? bytes[0] & 0x0F
                           : 1;
        return {visca::error_reply(to, 0, kSyntaxError)};
    }
    if (m.kind == visca::MessageKind::PositionInquiry || m.kind == visca::MessageKind::ZoomInquiry)
        return {inquiry_reply(model, now, m, u)};
    try {
        carry_out(model, now, m, u);
    } catch (const std::out_of_range&) {
        return {visca::error_reply(m.address, kCommandSocket, kNotExecutable)};
    }
    // The head takes the command at once: its completion follows the ACK without waiting
    // for the motion to end (the position inquiry shows that).
    return {visca::ack(m.address, kCommandSocket), visca::completion(m.address, kCommandSocket)};
}

std::vector<visca::Bytes> answer_visca_datagram(HeadModel& model, double now, std::span<const std::uint8_t> datagram,
                                                const ViscaUnits& u)
{
    visca::IpMessage in;
    try {
        in = visca::unwrap_ip(datagram);
    } catch (const visca::ViscaError&) {
        return {};
    }
    std::vector<visca::Bytes> out;
    if (in.payload_type == visca::kIpControl) {
        // RESET (01): the camera takes the sequence numbers as they come, so nothing to reset.
        if (in.payload == visca::Bytes{0x01})
            out.push_back(visca::wrap_ip(visca::kIpControlReply, in.sequence, in.payload));
        return out;
    }
    if (in.payload_type != visca::kIpCommand && in.payload_type != visca::kIpInquiry) return out;
    for (const visca::Bytes& reply : answer_visca(model, now, in.payload, u))
        out.push_back(visca::wrap_ip(visca::kIpReply, in.sequence, reply));
    return out;
}

namespace {

// A socket of `type` bound to host:port, non-blocking; invalid (errno set) when binding fails.
net::Fd bound_socket(int type, const std::string& host, std::uint16_t port)
{
    sockaddr_storage addr{};
    const socklen_t len = numeric_address(host, port, addr);
    net::Fd fd(::socket(addr.ss_family, type | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    const int one = 1;
    if (fd && type == SOCK_STREAM) ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (fd && ::bind(fd.get(), reinterpret_cast<sockaddr*>(&addr), len) != 0) fd.reset();
    return fd;
}

}  // namespace

ViscaResponder::ViscaResponder(const ViscaResponderConfig& config, HeadServer& head) : config_(config), head_(head)
{
    if (config_.units.units_per_deg <= 0.0 || config_.units.zoom_tele_units < 1 ||
        config_.units.zoom_tele_units > 0xFFFF)
        throw std::invalid_argument("VISCA units must be positive (zoom positions up to 65535)");
    sockaddr_storage addr{};
    numeric_address(config_.host, config_.port, addr);  // throws for a host that is not numeric
    if (!config_.allow_remote && !is_loopback_address(config_.host))
        throw std::invalid_argument("refusing to serve VISCA on " + config_.host +
                                    ": VISCA has no authentication, anyone who reaches it could move the head "
                                    "(allow it: headsim --allow-remote)");
    bind_sockets();
    thread_ = std::thread([this] { serve(); });
}

// UDP first; TCP on the port UDP got. Any free port may be taken for TCP: then try another.
void ViscaResponder::bind_sockets()
{
    for (int attempt = 0;; ++attempt) {
        udp_ = bound_socket(SOCK_DGRAM, config_.host, config_.port);
        if (!udp_) break;
        port_ = bound_port(udp_.get());
        listener_ = bound_socket(SOCK_STREAM, config_.host, port_);
        if (listener_ && ::listen(listener_.get(), 4) == 0) return;
        if (config_.port != 0 || attempt == 8) break;
    }
    throw std::runtime_error("cannot bind VISCA " + config_.host + ":" + std::to_string(config_.port) + ": " +
                             std::strerror(errno));
}

ViscaResponder::~ViscaResponder()
{
    stop_ = true;
    if (thread_.joinable()) thread_.join();
}

std::vector<visca::Bytes> ViscaResponder::answer(std::span<const std::uint8_t> message)
{
    std::vector<visca::Bytes> replies;
    head_.with_model([&](HeadModel& model, double now) { replies = answer_visca(model, now, message, config_.units); });
    return replies;
}

void ViscaResponder::serve()
{
    std::vector<pollfd> polled;
    while (!stop_) {
        polled = {{udp_.get(), POLLIN, 0}, {listener_.get(), POLLIN, 0}};
        for (const Stream& s : streams_) polled.push_back({s.fd.get(), POLLIN, 0});
        if (::poll(polled.data(), polled.size(), kPollMs) <= 0) continue;
        if (polled[0].revents) serve_datagram();
        // Streams before accepting, while the poll set still matches them.
        for (std::size_t i = streams_.size(); i-- > 0;)
            if (polled[2 + i].revents && !serve_stream(streams_[i])) streams_.erase(streams_.begin() + i);
        if (polled[1].revents) accept_stream();
    }
}

void ViscaResponder::serve_datagram()
{
    std::array<std::uint8_t, 512> buffer{};
    sockaddr_storage from{};
    socklen_t from_len = sizeof from;
    const ssize_t n =
        ::recvfrom(udp_.get(), buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n <= 0) return;
    std::vector<visca::Bytes> replies;
    head_.with_model([&](HeadModel& model, double now) {
        replies = answer_visca_datagram(model, now, std::span<const std::uint8_t>(buffer.data(), n), config_.units);
    });
    // A peer that cannot take a reply loses it, as over any UDP link.
    for (const visca::Bytes& r : replies)
        ::sendto(udp_.get(), r.data(), r.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), from_len);
}

// A camera serves few TCP peers: beyond kMaxStreams the one quiet the longest makes way.
void ViscaResponder::accept_stream()
{
    net::Fd fd(::accept4(listener_.get(), nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK));
    if (!fd) return;
    if (streams_.size() >= kMaxStreams)
        streams_.erase(std::min_element(streams_.begin(), streams_.end(), [](const Stream& a, const Stream& b) {
            return a.last_active < b.last_active;
        }));
    streams_.push_back(Stream{std::move(fd), {}, false, std::chrono::steady_clock::now()});
}

bool ViscaResponder::serve_stream(Stream& s)
{
    std::array<std::uint8_t, 256> buffer{};
    const ssize_t n = ::recv(s.fd.get(), buffer.data(), buffer.size(), 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) return false;
    if (n < 0) return true;
    s.last_active = std::chrono::steady_clock::now();
    std::vector<visca::Bytes> replies;
    for (std::uint8_t byte : std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(n))) {
        if (!s.discarding) s.input.push_back(byte);
        if (byte == 0xFF && s.discarding) {
            s.discarding = false;
        } else if (byte == 0xFF) {
            for (visca::Bytes& r : answer(s.input)) replies.push_back(std::move(r));
            s.input.clear();
        } else if (s.input.size() >= visca::kMaxMessageSize) {  // no end within 16 bytes
            replies.push_back(visca::error_reply(1, 0, kMessageLengthError));
            s.input.clear();
            s.discarding = true;
        }
    }
    // Replies are a few bytes: one that does not fit the socket's buffer means the peer
    // reads nothing, and it is dropped rather than waited for.
    for (const visca::Bytes& r : replies)
        if (::send(s.fd.get(), r.data(), r.size(), MSG_DONTWAIT | MSG_NOSIGNAL) != static_cast<ssize_t>(r.size()))
            return false;
    return true;
}

}  // namespace gc::headctl
