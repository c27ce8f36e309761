// The simulated head's mechanics: five axes with trapezoidal velocity profiles, soft limits,
// command latency and a seeded mechanical angle error. Time is passed in by the caller
// (seconds on any monotonic clock), so tests drive it with a fake clock.
#pragma once

#include "headctl/axes.hpp"

#include <cstdint>
#include <deque>
#include <map>
#include <random>
#include <vector>

namespace gc::headctl {

// The simulated head's default axes: a neck that pans +-170 deg and tilts -45..45 deg, and
// light, fast eyes that verge +-30 deg, and a 1x..20x zoom.
HeadLimits default_simulated_limits();

struct HeadModelConfig {
    HeadLimits limits = default_simulated_limits();
    double latency_s = 0.0;           // from a command's arrival to its effect
    double angle_error_deg = 0.0;     // std. deviation of the reached angle around a position target
    std::uint64_t seed = 1;           // of the angle error
    double velocity_timeout_s = 1.0;  // a velocity move not renewed within this stops (0 = never)
    double step_s = 0.001;            // integration step

    // Throws std::invalid_argument naming the bad field.
    void validate() const;
};

class HeadModel {
public:
    explicit HeadModel(const HeadModelConfig& config, double start_time_s = 0.0);

    // Commands arriving at now_s; each throws std::out_of_range if a target lies outside
    // the soft limits or a velocity exceeds the axis's maximum (nothing is applied then).
    void move_absolute(const AxisValues& targets_deg, double now_s);
    void move_relative(const AxisValues& offsets_deg, double now_s);
    void move_velocity(const AxisValues& velocities_dps, double now_s);
    void stop(double now_s);
    void home(double now_s);
    // A preset holds every axis's position at the moment it is saved (a moving head's, where
    // it is then); recalling moves there. Recalling one never saved throws std::out_of_range.
    void save_preset(int number, double now_s);
    void recall_preset(int number, double now_s);
    // The numbers of the presets saved so far, in increasing order.
    std::vector<int> preset_numbers() const;

    // Integrates the motion up to now_s (earlier times are ignored) and reports it.
    HeadState state(double now_s);
    const HeadLimits& limits() const { return config_.limits; }

private:
    enum class Mode { Hold, Position, Velocity };
    enum class Kind { Absolute, Velocity, Stop };
    struct AxisMotion {
        double position = 0.0;
        double velocity = 0.0;
        Mode mode = Mode::Hold;
        double target = 0.0;
        double commanded_velocity = 0.0;
        double velocity_deadline = 0.0;
    };
    struct Pending {
        double apply_time = 0.0;
        Kind kind = Kind::Stop;
        AxisValues values;
    };

    void check_targets(const AxisValues& targets) const;
    void enqueue(Kind kind, const AxisValues& values, double now_s);
    void apply(const Pending& p);
    void advance(double now_s);
    void step_axis(Axis axis, double dt);

    HeadModelConfig config_;
    std::array<AxisMotion, kAxisCount> axes_{};
    // The position each axis was last commanded to, counting queued commands: what a
    // relative move is relative to.
    std::array<double, kAxisCount> commanded_{};
    std::deque<Pending> pending_;
    std::map<int, AxisValues> presets_;
    double time_s_ = 0.0;
    std::mt19937_64 rng_;
    std::normal_distribution<double> error_{0.0, 1.0};
};

}  // namespace gc::headctl
