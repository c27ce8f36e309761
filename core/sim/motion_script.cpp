#include "sim/motion_script.hpp"

#include "stereo/head_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

double smoothstep(double x)
{
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

// Bounded, smooth and the identity near 0: keeps a coordinate inside +/- limit.
double soft_limit(double x, double limit) { return limit * std::tanh(x / limit); }

// LeaveReturn timing (seconds after the wave): hold, leave, stay out, come back.
constexpr double kHold = 1.0, kTravel = 2.8, kAway = 2.0;
constexpr double kRamp = 1.5;  // the motion fades in over this time after the wave

// Turns the hand about its palm so that the finger points at `target`, its palm turned to the
// cameras as far as that allows (the plane holds the finger and the line across the view).
void aim_at(HandPose& p, const cv::Vec3d& target)
{
    const cv::Vec3d d = target - p.palm_mm;
    const cv::Vec3d sight = p.palm_mm * (1.0 / std::max(cv::norm(p.palm_mm), 1e-6));
    if (!(cv::norm(d) > 1e-6)) return;
    const cv::Vec3d u = d * (1.0 / cv::norm(d));
    cv::Vec3d n = -(sight - sight.dot(u) * u);  // the normal nearest to facing the cameras
    if (!(cv::norm(n) > 1e-6)) n = u.cross(cv::Vec3d(1.0, 0.0, 0.0));  // pointing straight away
    n *= 1.0 / cv::norm(n);
    // Ry(yaw) Rx(pitch) maps (0, 0, -1) to n and (cos roll, -sin roll, 0) to u.
    p.pitch_deg = std::asin(std::clamp(n[1], -1.0, 1.0)) * 180.0 / kPi;
    p.yaw_deg = std::atan2(-n[0], -n[2]) * 180.0 / kPi;
    const cv::Vec3d in_plane = (rotation_about_y(p.yaw_deg) * rotation_about_x(p.pitch_deg)).t() * u;
    p.roll_deg = std::atan2(-in_plane[1], in_plane[0]) * 180.0 / kPi;
}

}  // namespace

double MotionScript::Channel::value(double tau) const
{
    double v = 0.0;
    for (std::size_t k = 0; k < amplitude.size(); ++k) v += amplitude[k] * std::sin(omega[k] * tau + phase[k]);
    return v;
}

MotionScript::MotionScript(const SceneConfig& c, double half_fov_x, double half_fov_y, double finger_length_mm,
                           Rng& rng)
    : motion_(c.motion), distance_(c.hand_distance_mm), half_fov_x_(half_fov_x), half_fov_y_(half_fov_y),
      baseline_(c.baseline_mm), finger_(finger_length_mm)
{
    const double D = distance_;
    rest_.palm_mm = {uniform(rng, -0.06, 0.06) * D, uniform(rng, -0.02, 0.06) * D, D};
    // Pointing obliquely upwards to one side or the other, the forearm below.
    rest_.roll_deg = uniform(rng, 0, 1) < 0.5 ? uniform(rng, 20, 70) : uniform(rng, 110, 160);
    rest_.yaw_deg = uniform(rng, -12, 12);
    rest_.pitch_deg = uniform(rng, -8, 8);
    if (c.aim_mm) aim_at(rest_, *c.aim_mm);

    // Total amplitude per channel: x, y, z in units of the distance, angles in degrees.
    std::array<double, kChannels> amp{};
    switch (c.motion) {
    case Motion::Static:
        break;
    case Motion::Translate:
        amp = {0.24 * D, 0.14 * D, 0, 0, 0, 0};
        break;
    case Motion::Rotate:
        amp = {0, 0, 0, 55, 0, 0};
        break;
    case Motion::Scale:
        amp = {0, 0, 0.32 * D, 0, 0, 0};
        break;
    case Motion::Yaw:
        amp = {0, 0, 0, 0, 50, 0};
        break;
    case Motion::Mixed:
        amp = {0.16 * D, 0.09 * D, 0.22 * D, 35, 25, 8};
        break;
    case Motion::LeaveReturn:
        amp = {0.12 * D, 0.07 * D, 0.1 * D, 20, 10, 0};
        break;
    }
    for (int i = 0; i < kChannels; ++i) {
        std::array<double, 3> w{uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0)};
        const double sum = w[0] + w[1] + w[2];
        for (int k = 0; k < 3; ++k) {
            channels_[i].amplitude[k] = amp[i] * w[k] / sum;
            channels_[i].omega[k] = 2.0 * kPi * uniform(rng, 0.06, 0.3);
            channels_[i].phase[k] = uniform(rng, 0, 2 * kPi);
        }
    }
    leave_start_ = kWaveSeconds + kHold;
    leave_side_ = uniform(rng, 0, 1) < 0.5 ? -1.0 : 1.0;

    limit_speed();
}

void MotionScript::set_pass(double start, double duration, cv::Vec2d target)
{
    pass_start_ = start;
    pass_duration_ = duration;
    pass_target_ = target;
    limit_speed();
}

void MotionScript::limit_speed()
{
    // Slow the script down (never change its path) until the fingertip stays under the
    // speed limit.
    for (int iter = 0; iter < 20; ++iter) {
        const double v = peak_speed();
        if (v <= kMaxSpeedMmS) break;
        const double k = 0.97 * kMaxSpeedMmS / v;
        for (auto& ch : channels_)
            for (double& o : ch.omega) o *= k;
    }
}

HandPose MotionScript::at(double t) const
{
    HandPose p = rest_;
    // The wave: the hand swings about the wrist, side to side.
    if (t < kWaveSeconds) {
        const double env = std::pow(std::sin(kPi * t / kWaveSeconds), 2);
        const double swing = 14.0 * env * std::sin(2.0 * kPi * 1.5 * t);
        p.roll_deg += swing;
        const double a = p.roll_deg * kPi / 180.0;
        const double lever = 0.6 * finger_ * swing * kPi / 180.0;  // palm moves on its arc
        p.palm_mm[0] += -std::sin(a) * lever;
        p.palm_mm[1] += -std::cos(a) * lever;
        return p;
    }
    double tau = t - kWaveSeconds;
    double away = 0.0;
    if (motion_ == Motion::LeaveReturn) {
        const double s = t - leave_start_;
        away = smoothstep(s / kTravel) - smoothstep((s - kTravel - kAway) / kTravel);
        const double back = kHold + 2.0 * kTravel + kAway;  // the motion starts once back
        tau = t - kWaveSeconds - back;
        if (tau < 0.0) tau = 0.0;
    }
    const double ramp = smoothstep(tau / kRamp);
    // Offsets from the rest pose, bounded so the hand stays in both views and the pose
    // stays anatomical; zero offset leaves the rest pose exactly.
    auto bounded = [](double rest, double offset, double limit) {
        return rest + soft_limit(offset, std::max(1e-3, limit - std::abs(rest)));
    };
    p.palm_mm[2] = std::max(p.palm_mm[2] + ramp * channels_[Z].value(tau), 0.45 * distance_);
    const double z = p.palm_mm[2];
    const double reach = 0.75 * finger_;  // of the hand beyond its palm centre
    const double lim_x = std::max(30.0, 0.92 * (z * half_fov_x_ - 0.5 * baseline_ - reach));
    const double lim_y = std::max(30.0, 0.92 * (z * half_fov_y_ - reach));
    p.palm_mm[0] = bounded(rest_.palm_mm[0], ramp * channels_[X].value(tau), lim_x);
    p.palm_mm[1] = bounded(rest_.palm_mm[1], ramp * channels_[Y].value(tau), lim_y);
    p.roll_deg = 90.0 + bounded(rest_.roll_deg - 90.0, ramp * channels_[Roll].value(tau), 105.0);
    p.yaw_deg = bounded(rest_.yaw_deg, ramp * channels_[Yaw].value(tau), 60.0);
    p.pitch_deg = bounded(rest_.pitch_deg, ramp * channels_[Pitch].value(tau), 30.0);
    if (pass_duration_ > 0.0 && t > pass_start_ && t < pass_start_ + pass_duration_) {
        const double w = std::pow(std::sin(kPi * (t - pass_start_) / pass_duration_), 2);
        p.palm_mm[0] += w * (pass_target_[0] * z - p.palm_mm[0]);
        p.palm_mm[1] += w * (pass_target_[1] * z - p.palm_mm[1]);
    }
    if (away > 0.0) {
        // Out past the edge of both views, hand and all.
        const double out = z * half_fov_x_ + 0.5 * baseline_ + 1.6 * finger_ + std::abs(rest_.palm_mm[0]);
        p.palm_mm[0] += leave_side_ * away * out;
    }
    return p;
}

double MotionScript::peak_speed() const
{
    constexpr double dt = 1.0 / 100.0;
    auto tip = [&](double t) {
        const HandPose p = at(t);
        const double r = p.roll_deg * kPi / 180.0, y = p.yaw_deg * kPi / 180.0;
        // Direction of the finger (the exact frame does not matter for a speed bound).
        const cv::Vec3d u(std::cos(r) * std::cos(y), -std::sin(r), -std::cos(r) * std::sin(y));
        return p.palm_mm + finger_ * u;
    };
    double peak = 0.0;
    cv::Vec3d prev = tip(kWaveSeconds);
    for (double t = kWaveSeconds + dt; t < kWaveSeconds + 60.0; t += dt) {
        const cv::Vec3d cur = tip(t);
        if (motion_ != Motion::LeaveReturn ||
            t > leave_start_ + 2.0 * kTravel + kAway)  // the exit and return are timed apart
            peak = std::max(peak, cv::norm(cur - prev) / dt);
        prev = cur;
    }
    return peak;
}

}  // namespace gc::sim
