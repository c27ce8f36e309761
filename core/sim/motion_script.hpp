// Scripted hand motions: a wave, then the chosen motion as a sum of slow sinusoids with
// seeded frequencies and phases (different seeds, different paths), limited to a plausible
// speed and softly held inside both views.
#pragma once

#include "sim/appearance.hpp"
#include "sim/scene.hpp"

#include <array>

namespace gc::sim {

class MotionScript {
public:
    // `half_fov_x`, `half_fov_y`: tangents of the half fields of view, to keep the hand in view.
    MotionScript(const SceneConfig& config, double half_fov_x, double half_fov_y, double finger_length_mm, Rng& rng);

    HandPose at(double t) const;

    // face-pass: between `start` and `start + duration` seconds the palm's view direction
    // (x / z, y / z) is blended towards `target` and back (sin^2), so at the middle the
    // palm is exactly on that ray, whatever the motion does. The speed limit is re-applied.
    void set_pass(double start, double duration, cv::Vec2d target);

    static constexpr double kWaveSeconds = 1.2;
    static constexpr double kMaxSpeedMmS = 480.0;

private:
    struct Channel {
        std::array<double, 3> amplitude{};
        std::array<double, 3> omega{};  // rad/s
        std::array<double, 3> phase{};
        double value(double tau) const;
    };
    enum Index { X, Y, Z, Roll, Yaw, Pitch, kChannels };

    double peak_speed() const;
    void limit_speed();

    Motion motion_;
    double distance_;
    double half_fov_x_, half_fov_y_, baseline_;
    double finger_;
    HandPose rest_;
    std::array<Channel, kChannels> channels_;
    double leave_start_ = 0.0;  // LeaveReturn: when the hand starts to leave
    double leave_side_ = 1.0;
    double pass_start_ = 0.0, pass_duration_ = 0.0;  // duration 0: no pass
    cv::Vec2d pass_target_;
};

}  // namespace gc::sim
