#include "headctl/pelco_backend.hpp"

#include "headctl/serial_port.hpp"

#include <algorithm>
#include <cmath>

namespace gc::headctl {

namespace {

// Hundredths of a degree, 0..35999 clockwise (right, or up for tilt), as signed degrees.
double to_degrees(int hundredths)
{
    const double deg = hundredths / 100.0;
    return deg > 180.0 ? deg - 360.0 : deg;
}

int to_hundredths(double deg)
{
    const long v = std::lround(deg * 100.0);
    return static_cast<int>(((v % 36000) + 36000) % 36000);
}

int direction(double v) { return std::abs(v) < 1e-6 ? 0 : (v > 0 ? 1 : -1); }

}  // namespace

PelcoSettings PelcoSettings::from_uri(const HeadUri& uri)
{
    PelcoSettings s;
    s.address = address_param(uri, 255);
    s.baud = baud_param(uri, s.baud);
    s.pan_max_speed_dps = uri.number_param("pan_max_speed_dps", s.pan_max_speed_dps, 0.1, 1000.0);
    s.tilt_max_speed_dps = uri.number_param("tilt_max_speed_dps", s.tilt_max_speed_dps, 0.1, 1000.0);
    s.zoom_max = uri.number_param("zoom_max", s.zoom_max, 1.0, 1000.0);
    s.reply_timeout = reply_timeout_param(uri, s.reply_timeout);
    return s;
}

PelcoBackend::PelcoBackend(std::string path, PelcoSettings settings) : path_(std::move(path)), settings_(settings) {}

void PelcoBackend::open(Deadline)
{
    close();
    fd_ = open_serial_port(path_, settings_.baud);
}

void PelcoBackend::close()
{
    fd_.reset();
    stream_.clear();
    drive_ = {};
    last_pose_.reset();
}

void PelcoBackend::write(const pelco::Message& m, Deadline deadline)
{
    if (!fd_) throw net::NetError("not connected");
    net::send_all(fd_.get(), std::span<const std::uint8_t>(m), deadline);
}

int PelcoBackend::ask(const pelco::Message& query, pelco::Reading reading, Deadline deadline)
{
    write(query, deadline);
    const Deadline end = std::min(deadline, net::Clock::now() + settings_.reply_timeout);
    std::array<std::uint8_t, 64> buffer{};
    for (;;) {
        // Resynchronise on the next FF; a message whose checksum fails gives up its FF only.
        while (stream_.size() >= 7) {
            const auto sync = std::find(stream_.begin(), stream_.end(), 0xFF);
            stream_.erase(stream_.begin(), sync);
            if (stream_.size() < 7) break;
            std::array<std::uint8_t, 7> m{};
            std::copy_n(stream_.begin(), 7, m.begin());
            try {
                const auto report = pelco::parse_report(m);
                stream_.erase(stream_.begin(), stream_.begin() + 7);
                if (report && report->reading == reading && report->address == settings_.address) return report->value;
            } catch (const pelco::PelcoError&) {
                stream_.erase(stream_.begin());
            }
        }
        if (std::find(stream_.begin(), stream_.end(), 0xFF) == stream_.end()) stream_.clear();  // noise
        const auto n = net::receive_some(fd_.get(), buffer, end);
        if (!n) throw net::NetError(name() + " did not answer in time");
        stream_.insert(stream_.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*n));
        if (net::Clock::now() >= end) throw net::NetError(name() + " did not answer in time");
    }
}

HeadState PelcoBackend::query_state(Deadline deadline)
{
    const int a = settings_.address;
    HeadState s;
    s.pose.pan_deg = to_degrees(ask(pelco::query_pan(a), pelco::Reading::Pan, deadline));
    s.pose.tilt_deg = to_degrees(ask(pelco::query_tilt(a), pelco::Reading::Tilt, deadline));
    if (has_zoom())
        s.pose.zoom =
            1.0 + ask(pelco::query_zoom(a), pelco::Reading::Zoom, deadline) / 65535.0 * (settings_.zoom_max - 1.0);
    flag_motion_since(s, last_pose_);
    return s;
}

void PelcoBackend::send_absolute(const HeadCommand& c, Deadline deadline)
{
    const int a = settings_.address;
    const bool relative = c.kind == CommandKind::Relative;
    const HeadPose here = relative ? (last_pose_ ? *last_pose_ : query_state(deadline).pose) : HeadPose{};
    const auto target = [&](Axis axis) { return c.values.get(axis) + (relative ? axis_value(here, axis) : 0.0); };
    if (c.values.has(Axis::Pan)) write(pelco::set_pan(a, to_hundredths(target(Axis::Pan))), deadline);
    if (c.values.has(Axis::Tilt)) write(pelco::set_tilt(a, to_hundredths(target(Axis::Tilt))), deadline);
    if (c.values.has(Axis::Zoom)) {
        const double z = target(Axis::Zoom);
        if (!(z >= 1.0 && z <= settings_.zoom_max)) throw HeadRejected(name() + ": zoom outside [1, zoom_max]");
        write(pelco::set_zoom(a, static_cast<int>(std::lround((z - 1.0) / (settings_.zoom_max - 1.0) * 65535.0))),
              deadline);
    }
}

void PelcoBackend::send_velocity(const HeadCommand& c, Deadline deadline)
{
    if (c.values.has(Axis::Pan)) drive_[0] = c.values.get(Axis::Pan);
    if (c.values.has(Axis::Tilt)) drive_[1] = c.values.get(Axis::Tilt);
    if (c.values.has(Axis::Zoom)) drive_[2] = c.values.get(Axis::Zoom);
    const auto code = [](double v, double max) {
        return std::clamp(static_cast<int>(std::lround(std::abs(v) / max * pelco::kMaxSpeed)), 1, pelco::kMaxSpeed);
    };
    pelco::Drive d;
    d.pan = direction(drive_[0]);
    d.tilt = direction(drive_[1]);
    d.zoom = direction(drive_[2]);
    d.pan_speed = code(drive_[0], settings_.pan_max_speed_dps);
    d.tilt_speed = code(drive_[1], settings_.tilt_max_speed_dps);
    write(pelco::drive(settings_.address, d), deadline);
}

void PelcoBackend::send(const HeadCommand& c, Deadline deadline)
{
    if (c.values.has(Axis::VergeLeft) || c.values.has(Axis::VergeRight))
        throw HeadRejected(name() + " has no vergence axes");
    if (c.values.has(Axis::Zoom) && !has_zoom())
        throw HeadRejected(name() + " has no zoom axis (the URI's zoom_max is 1)");
    const int a = settings_.address;
    try {
        switch (c.kind) {
        case CommandKind::Stop:
            drive_ = {};
            write(pelco::stop(a), deadline);
            return;
        case CommandKind::Home: {
            drive_ = {};
            HeadCommand home{CommandKind::Absolute, {}};
            home.values.set(Axis::Pan, 0.0);
            home.values.set(Axis::Tilt, 0.0);
            if (has_zoom()) home.values.set(Axis::Zoom, 1.0);
            send_absolute(home, deadline);
            return;
        }
        case CommandKind::Absolute:
        case CommandKind::Relative:
            drive_ = {};
            send_absolute(c, deadline);
            return;
        case CommandKind::Velocity:
            send_velocity(c, deadline);
            return;
        // Pelco-D numbers presets from 1: preset n of the library is the camera's n + 1.
        case CommandKind::SavePreset:
            write(pelco::preset(a, pelco::PresetAction::Set, c.preset + 1), deadline);
            return;
        case CommandKind::RecallPreset:
            write(pelco::preset(a, pelco::PresetAction::GoTo, c.preset + 1), deadline);
            return;
        }
    } catch (const pelco::PelcoError& e) {
        throw HeadRejected(name() + ": " + e.what());
    }
}

}  // namespace gc::headctl
