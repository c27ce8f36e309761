#include "headctl/sim/head_model.hpp"

#include "headctl/braking.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gc::headctl {

namespace {
// A burst of commands faster than the latency drains cannot grow memory: the oldest go.
constexpr std::size_t kMaxPending = 64;
constexpr double kSettleDeg = 1e-6;

std::string fmt(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}
}  // namespace

HeadLimits default_simulated_limits()
{
    HeadLimits l;
    l[Axis::Pan] = AxisLimits{-170.0, 170.0, 120.0, 400.0};
    l[Axis::Tilt] = AxisLimits{-45.0, 45.0, 90.0, 300.0};
    l[Axis::VergeLeft] = AxisLimits{-30.0, 30.0, 200.0, 1000.0};
    l[Axis::VergeRight] = AxisLimits{-30.0, 30.0, 200.0, 1000.0};
    // A 20x zoom lens that runs from end to end in about 2.5 s.
    l[Axis::Zoom] = AxisLimits{1.0, 20.0, 8.0, 30.0};
    return l;
}

void HeadModelConfig::validate() const
{
    headctl::validate(limits);
    if (!std::isfinite(latency_s) || latency_s < 0.0 || latency_s > 10.0)
        throw std::invalid_argument("latency must be in [0, 10] s");
    if (!std::isfinite(angle_error_deg) || angle_error_deg < 0.0 || angle_error_deg > 10.0)
        throw std::invalid_argument("angle error must be in [0, 10] deg");
    if (!std::isfinite(velocity_timeout_s) || velocity_timeout_s < 0.0)
        throw std::invalid_argument("velocity timeout must be >= 0 s");
    if (!std::isfinite(step_s) || step_s <= 0.0 || step_s > 0.05)
        throw std::invalid_argument("integration step must be in (0, 0.05] s");
}

HeadModel::HeadModel(const HeadModelConfig& config, double start_time_s)
    : config_(config), time_s_(start_time_s), rng_(config.seed)
{
    config_.validate();
    for (Axis a : kAllAxes) {
        axes_[static_cast<std::size_t>(a)].position = home_value(a);
        commanded_[static_cast<std::size_t>(a)] = home_value(a);
    }
}

void HeadModel::check_targets(const AxisValues& targets) const
{
    for (Axis a : kAllAxes) {
        if (!targets.has(a)) continue;
        const AxisLimits& l = config_.limits[a];
        const double t = targets.get(a);
        if (!std::isfinite(t) || t < l.min_deg || t > l.max_deg)
            throw std::out_of_range(std::string(axis_name(a)) + " target " + fmt(t) + " deg is outside [" +
                                    fmt(l.min_deg) + ", " + fmt(l.max_deg) + "]");
    }
}

void HeadModel::move_absolute(const AxisValues& targets, double now_s)
{
    check_targets(targets);
    enqueue(Kind::Absolute, targets, now_s);
}

void HeadModel::move_relative(const AxisValues& offsets, double now_s)
{
    AxisValues targets;
    for (Axis a : kAllAxes)
        if (offsets.has(a)) targets.set(a, commanded_[static_cast<std::size_t>(a)] + offsets.get(a));
    check_targets(targets);
    enqueue(Kind::Absolute, targets, now_s);
}

void HeadModel::move_velocity(const AxisValues& velocities, double now_s)
{
    for (Axis a : kAllAxes) {
        if (!velocities.has(a)) continue;
        const double v = velocities.get(a);
        const double vmax = config_.limits[a].max_velocity_dps;
        if (!std::isfinite(v) || std::abs(v) > vmax)
            throw std::out_of_range(std::string(axis_name(a)) + " velocity " + fmt(v) + " deg/s exceeds the maximum " +
                                    fmt(vmax));
    }
    enqueue(Kind::Velocity, velocities, now_s);
}

void HeadModel::stop(double now_s) { enqueue(Kind::Stop, AxisValues{}, now_s); }

void HeadModel::home(double now_s)
{
    AxisValues home;
    for (Axis a : kAllAxes) home.set(a, home_value(a));
    enqueue(Kind::Absolute, home, now_s);
}

void HeadModel::save_preset(int number, double now_s)
{
    const HeadState s = state(now_s);
    AxisValues here;
    for (Axis a : kAllAxes) here.set(a, axis_value(s.pose, a));
    presets_[number] = here;
}

void HeadModel::recall_preset(int number, double now_s)
{
    const auto p = presets_.find(number);
    if (p == presets_.end()) throw std::out_of_range("preset " + std::to_string(number) + " was never saved");
    move_absolute(p->second, now_s);
}

void HeadModel::enqueue(Kind kind, const AxisValues& values, double now_s)
{
    advance(now_s);
    for (Axis a : kAllAxes) {
        const auto i = static_cast<std::size_t>(a);
        if (kind == Kind::Absolute && values.has(a)) commanded_[i] = values.get(a);
    }
    Pending p{std::max(now_s, time_s_) + config_.latency_s, kind, values};
    if (config_.latency_s <= 0.0) {
        apply(p);
        return;
    }
    if (pending_.size() == kMaxPending) pending_.pop_front();
    pending_.push_back(std::move(p));
}

void HeadModel::apply(const Pending& p)
{
    for (Axis a : kAllAxes) {
        AxisMotion& m = axes_[static_cast<std::size_t>(a)];
        const AxisLimits& l = config_.limits[a];
        switch (p.kind) {
        case Kind::Stop:
            m.mode = Mode::Hold;
            break;
        case Kind::Absolute:
            if (!p.values.has(a)) break;
            m.mode = Mode::Position;
            // Where the axis really comes to rest: the command plus a mechanical angle error
            // (a zoom lens's stop is not an angle).
            m.target = p.values.get(a);
            if (a != Axis::Zoom) m.target += config_.angle_error_deg * error_(rng_);
            m.target = std::clamp(m.target, l.min_deg, l.max_deg);
            break;
        case Kind::Velocity:
            if (!p.values.has(a)) break;
            m.mode = Mode::Velocity;
            m.commanded_velocity = p.values.get(a);
            m.velocity_deadline = p.apply_time + config_.velocity_timeout_s;
            break;
        }
    }
}

void HeadModel::step_axis(Axis axis, double dt)
{
    AxisMotion& m = axes_[static_cast<std::size_t>(axis)];
    const AxisLimits& l = config_.limits[axis];
    const double a = l.max_acceleration_dps2;
    if (m.mode == Mode::Velocity && config_.velocity_timeout_s > 0.0 && time_s_ >= m.velocity_deadline)
        m.mode = Mode::Hold;

    double desired = 0.0;
    if (m.mode == Mode::Position) {
        // Fastest approach that can still brake to rest exactly at the target.
        const double error = m.target - m.position;
        const double dir = error >= 0.0 ? 1.0 : -1.0;
        desired = dir * std::min(l.max_velocity_dps, braking_speed(std::abs(error), dir * m.velocity, a, dt));
    } else if (m.mode == Mode::Velocity) {
        desired = m.commanded_velocity;
    }
    // Brake so as to stop at a soft limit rather than run into it.
    desired = std::min(desired, braking_speed(l.max_deg - m.position, m.velocity, a, dt));
    desired = std::max(desired, -braking_speed(m.position - l.min_deg, -m.velocity, a, dt));

    const double dv = std::clamp(desired - m.velocity, -a * dt, a * dt);
    const double next = m.velocity + dv;
    m.position = std::clamp(m.position + 0.5 * (m.velocity + next) * dt, l.min_deg, l.max_deg);
    m.velocity = next;
    if (m.mode == Mode::Position && std::abs(m.target - m.position) < kSettleDeg && std::abs(m.velocity) <= a * dt) {
        m.position = m.target;
        m.velocity = 0.0;
        m.mode = Mode::Hold;
    }
    if (m.mode == Mode::Hold && std::abs(m.velocity) <= a * dt) m.velocity = 0.0;
}

void HeadModel::advance(double now_s)
{
    if (!std::isfinite(now_s)) throw std::invalid_argument("head model time is not finite");
    while (time_s_ < now_s) {
        while (!pending_.empty() && pending_.front().apply_time <= time_s_) {
            apply(pending_.front());
            pending_.pop_front();
        }
        double dt = std::min(config_.step_s, now_s - time_s_);
        if (!pending_.empty()) dt = std::min(dt, std::max(pending_.front().apply_time - time_s_, 1e-9));
        for (Axis a : kAllAxes) step_axis(a, dt);
        time_s_ += dt;
    }
    while (!pending_.empty() && pending_.front().apply_time <= time_s_) {
        apply(pending_.front());
        pending_.pop_front();
    }
}

HeadState HeadModel::state(double now_s)
{
    advance(now_s);
    HeadState s;
    s.server_time_us = static_cast<std::int64_t>(std::llround(time_s_ * 1e6));
    for (Axis a : kAllAxes) {
        const AxisMotion& m = axes_[static_cast<std::size_t>(a)];
        set_axis_value(s.pose, a, m.position);
        s.moving[static_cast<std::size_t>(a)] = m.velocity != 0.0 || m.mode == Mode::Position;
    }
    return s;
}

std::vector<int> HeadModel::preset_numbers() const
{
    std::vector<int> out;
    for (const auto& [number, pose] : presets_) out.push_back(number);
    return out;
}

}  // namespace gc::headctl
