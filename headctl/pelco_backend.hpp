// A pan-tilt(-zoom) head speaking Pelco-D on a serial line (RS-485 through an adapter).
// Pelco-D acknowledges nothing: commands are written and taken as accepted; positions are
// read with the extended queries (0x51, 0x53, 0x55), which a camera answers or not.
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/pelco_d.hpp"

#include <chrono>
#include <vector>

namespace gc::headctl {

struct PelcoSettings {
    int address = 1;
    int baud = 2400;
    double pan_max_speed_dps = 100.0;  // the speed of code 0x3F
    double tilt_max_speed_dps = 60.0;
    double zoom_max = 1.0;  // magnification at zoom position 0xFFFF; 1: no zoom axis
    std::chrono::milliseconds reply_timeout{500};

    static PelcoSettings from_uri(const HeadUri& uri);  // throws std::invalid_argument
};

class PelcoBackend final : public HeadBackend {
public:
    PelcoBackend(std::string path, PelcoSettings settings);

    void open(Deadline deadline) override;
    void close() override;
    HeadState query_state(Deadline deadline) override;
    void send(const HeadCommand& command, Deadline deadline) override;
    std::optional<HeadLimits> query_limits(Deadline) override { return std::nullopt; }
    HeadLimits assumed_limits() const override { return limits_with_zoom(*this, settings_.zoom_max, 8.0); }
    std::array<bool, kAxisCount> axes() const override { return {true, true, false, false, has_zoom()}; }
    std::string name() const override { return "pelco-d://" + path_; }

private:
    bool has_zoom() const { return settings_.zoom_max > 1.0; }
    void write(const pelco::Message& message, Deadline deadline);
    // Asks one position and waits for its report, skipping other messages and noise.
    int ask(const pelco::Message& query, pelco::Reading reading, Deadline deadline);
    void send_absolute(const HeadCommand& command, Deadline deadline);
    void send_velocity(const HeadCommand& command, Deadline deadline);

    std::string path_;
    PelcoSettings settings_;
    net::Fd fd_;
    std::vector<std::uint8_t> stream_;
    std::array<double, 3> drive_{};  // last velocity of pan, tilt, zoom: one message drives all three
    std::optional<HeadPose> last_pose_;
};

}  // namespace gc::headctl
