#include "headctl/steering/fixate_controller.hpp"

#include "headctl/braking.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gc::headctl {

namespace {
constexpr double kRadToDeg = 57.29577951308232;
}

void FixateConfig::validate() const
{
    auto check = [](double v, bool ok, const char* name) {
        if (!std::isfinite(v) || !ok) throw std::invalid_argument(std::string("fixate controller: bad ") + name);
    };
    check(dead_band_deg, dead_band_deg >= 0.0, "dead band (must be >= 0)");
    check(release_band_deg, release_band_deg >= dead_band_deg, "release band (must be >= the dead band)");
    check(gain_per_s, gain_per_s > 0.0, "gain (must be > 0)");
    check(feed_forward, feed_forward >= 0.0 && feed_forward <= 2.0, "feed-forward (must be in [0, 2])");
    check(rate_dead_band_dps, rate_dead_band_dps >= 0.0, "rate dead band (must be >= 0)");
    check(max_velocity_dps, max_velocity_dps > 0.0, "maximum velocity (must be > 0)");
    check(max_acceleration_dps2, max_acceleration_dps2 > 0.0, "maximum acceleration (must be > 0)");
    check(limit_margin_deg, limit_margin_deg >= 0.0, "limit margin (must be >= 0)");
    check(hold_s, hold_s >= 0.0, "hold time (must be >= 0)");
    check(widen_after_s, widen_after_s >= 0.0, "widen-after time (must be >= 0)");
    check(widen_rate, widen_rate > 0.0, "widening rate (must be > 0)");
    if (home_preset && (*home_preset < 0 || *home_preset > kMaxPreset))
        throw std::invalid_argument("fixate: home preset must be in 0..127");
    check(head_latency_s, head_latency_s >= 0.0 && head_latency_s <= 1.0, "head latency (must be in [0, 1] s)");
    headctl::validate(limits);
}

FixateObservation offset_from_image(double dx_px, double dy_px, double fx_px, double fy_px)
{
    if (!(fx_px > 0.0) || !(fy_px > 0.0) || !std::isfinite(fx_px) || !std::isfinite(fy_px))
        throw std::invalid_argument("image offset: focal lengths must be finite and > 0");
    if (!std::isfinite(dx_px) || !std::isfinite(dy_px))
        throw std::invalid_argument("image offset: pixel offsets must be finite");
    FixateObservation o;
    o.valid = true;
    o.offset_pan_deg = std::atan2(dx_px, fx_px) * kRadToDeg;
    o.offset_tilt_deg = -std::atan2(dy_px, fy_px) * kRadToDeg;  // image y points down
    return o;
}

FixateController::FixateController(const FixateConfig& config) : config_(config) { config_.validate(); }

void FixateController::reset()
{
    velocity_ = {};
    settled_ = {};
    lost_s_ = 0.0;
    homed_ = false;
    widening_ = false;
}

double FixateController::axis_velocity(std::size_t i, double offset, double rate, double position,
                                       const AxisLimits& limits, double dt)
{
    const FixateConfig& c = config_;
    // Dead band with hysteresis: a settled axis stays put until the offset clearly grows.
    const double magnitude = std::abs(offset);
    if (magnitude <= c.dead_band_deg)
        settled_[i] = true;
    else if (magnitude > c.release_band_deg)
        settled_[i] = false;
    const double error = settled_[i] ? 0.0 : offset;

    // Proportional, but never faster than what can still brake to rest at the target
    // within one control period: this is what keeps the step response from overshooting.
    const double a = c.max_acceleration_dps2;
    const double dir = error >= 0.0 ? 1.0 : -1.0;
    double v =
        dir * std::min(c.gain_per_s * std::abs(error), braking_speed(std::abs(error), dir * velocity_[i], a, dt));
    if (std::abs(rate) > c.rate_dead_band_dps) v += c.feed_forward * rate;
    v = std::clamp(v, -c.max_velocity_dps, c.max_velocity_dps);

    // Soft limits: brake so as to stop a margin inside them, counting the way the head
    // still travels before a command takes effect.
    const double coast = std::abs(velocity_[i]) * c.head_latency_s;
    const double room_up = limits.max_deg - c.limit_margin_deg - position - (velocity_[i] > 0 ? coast : 0.0);
    const double room_down = position - (limits.min_deg + c.limit_margin_deg) - (velocity_[i] < 0 ? coast : 0.0);
    v = std::clamp(v, -braking_speed(room_down, -velocity_[i], a, dt), braking_speed(room_up, velocity_[i], a, dt));

    // Rate limit: the command changes by at most a * dt per step.
    v = std::clamp(v, velocity_[i] - a * dt, velocity_[i] + a * dt);
    velocity_[i] = v;
    return v;
}

std::optional<HeadCommand> FixateController::update(const FixateObservation& seen, const HeadPose& head, double dt_s)
{
    if (!std::isfinite(dt_s) || dt_s <= 0.0 || dt_s > 10.0)
        throw std::invalid_argument("fixate controller: time step must be in (0, 10] s");
    const bool finite = std::isfinite(seen.offset_pan_deg) && std::isfinite(seen.offset_tilt_deg) &&
                        std::isfinite(seen.rate_pan_dps) && std::isfinite(seen.rate_tilt_dps);
    if (seen.valid && !finite) throw std::invalid_argument("fixate controller: observation is not finite");

    HeadCommand command;
    command.kind = CommandKind::Velocity;
    if (seen.valid) {
        lost_s_ = 0.0;
        homed_ = false;
        command.values.set(Axis::Pan, axis_velocity(0, seen.offset_pan_deg, seen.rate_pan_dps, head.pan_deg,
                                                    config_.limits[Axis::Pan], dt_s));
        command.values.set(Axis::Tilt, axis_velocity(1, seen.offset_tilt_deg, seen.rate_tilt_dps, head.tilt_deg,
                                                     config_.limits[Axis::Tilt], dt_s));
        if (widening_) command.values.set(Axis::Zoom, 0.0);  // found again: the lens stops where it is
        widening_ = false;
        return command;
    }
    // Lost: brake and hold where the hand was last seen (it often reappears there), then home.
    if (homed_) return std::nullopt;
    lost_s_ += dt_s;
    if (lost_s_ >= config_.hold_s) {
        homed_ = true;
        widening_ = false;  // the home move sets the zoom: nothing to stop later
        velocity_ = {};
        settled_ = {};
        if (config_.home_preset) return preset_command(CommandKind::RecallPreset, *config_.home_preset);
        return HeadCommand{CommandKind::Home, {}};
    }
    const double step = config_.max_acceleration_dps2 * dt_s;
    for (std::size_t i = 0; i < 2; ++i) velocity_[i] = std::clamp(0.0, velocity_[i] - step, velocity_[i] + step);
    command.values.set(Axis::Pan, velocity_[0]);
    command.values.set(Axis::Tilt, velocity_[1]);
    if (config_.widen_after_s > 0.0 && lost_s_ >= config_.widen_after_s) {
        command.values.set(Axis::Zoom, -std::min(config_.widen_rate, config_.limits[Axis::Zoom].max_velocity_dps));
        widening_ = true;
    }
    return command;
}

}  // namespace gc::headctl
