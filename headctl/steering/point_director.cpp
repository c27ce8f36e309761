#include "headctl/steering/point_director.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gc::headctl {

void PointDirectorConfig::validate() const
{
    auto check = [](double v, bool ok, const char* name) {
        if (!std::isfinite(v) || !ok) throw std::invalid_argument(std::string("point director: bad ") + name);
    };
    check(look_s, look_s > 0.0, "look time (must be > 0)");
    check(same_target_deg, same_target_deg >= 0.0, "same-target angle (must be >= 0)");
    check(arrive_deg, arrive_deg > 0.0, "arrival angle (must be > 0)");
    check(travel_timeout_s, travel_timeout_s > 0.0, "travel timeout (must be > 0)");
    check(lowered_s, lowered_s >= 0.0, "lowered-hand time (must be >= 0)");
}

std::string_view to_string(PointPhase phase)
{
    switch (phase) {
    case PointPhase::Following:
        return "following";
    case PointPhase::Turning:
        return "turning";
    case PointPhase::Looking:
        return "looking";
    case PointPhase::Returning:
        return "returning";
    }
    return "unknown";
}

PointDirector::PointDirector(const PointDirectorConfig& config) : config_(config) { config_.validate(); }

void PointDirector::reset()
{
    phase_ = PointPhase::Following;
    answered_.reset();
    hand_back_ = false;
    last_pointing_s_.reset();
}

void PointDirector::set_look_time(double look_s)
{
    PointDirectorConfig c = config_;
    c.look_s = look_s;
    c.validate();
    config_ = c;
}

bool PointDirector::same_as(const PointAim& a, const PointAim& b) const
{
    return std::hypot(a.pan_deg - b.pan_deg, a.tilt_deg - b.tilt_deg) <= config_.same_target_deg;
}

bool PointDirector::arrived(double pan_deg, double tilt_deg, const HeadPose& head) const
{
    return std::abs(head.pan_deg - pan_deg) <= config_.arrive_deg &&
           std::abs(head.tilt_deg - tilt_deg) <= config_.arrive_deg;
}

PointStep PointDirector::turn_to(double t_s, const PointAim& aim)
{
    phase_ = PointPhase::Turning;
    phase_start_s_ = t_s;
    aim_ = aim;
    return {PointStep::Kind::Aim, aim, {}};
}

void PointDirector::watch_for_lowered_hand(double t_s, bool pointing, bool hand_seen)
{
    if (!answered_) return;
    hand_back_ = hand_back_ || hand_seen;
    if (pointing || !last_pointing_s_) last_pointing_s_ = t_s;
    // Frames before the tracker found the hand again say nothing about the speaker.
    if (!hand_back_) last_pointing_s_ = t_s;
    if (t_s - *last_pointing_s_ >= config_.lowered_s) answered_.reset();
}

PointStep PointDirector::update(double t_s, const std::optional<PointAim>& pick, bool pointing, bool hand_seen,
                                const HeadPose& head)
{
    const PointStep hold{PointStep::Kind::Hold, {}, {}};
    switch (phase_) {
    case PointPhase::Following:
        if (pick && !(answered_ && same_as(*pick, *answered_))) {
            return_pose_ = head;
            return turn_to(t_s, *pick);
        }
        watch_for_lowered_hand(t_s, pointing, hand_seen);
        return {};
    case PointPhase::Turning:
    case PointPhase::Looking:
        // A new pointing held while the head looks moves the look there.
        if (pick && !same_as(*pick, aim_)) return turn_to(t_s, *pick);
        if (phase_ == PointPhase::Turning &&
            (arrived(aim_.pan_deg, aim_.tilt_deg, head) || t_s - phase_start_s_ >= config_.travel_timeout_s)) {
            phase_ = PointPhase::Looking;
            look_until_s_ = t_s + config_.look_s;
        }
        if (phase_ == PointPhase::Looking && t_s >= look_until_s_) {
            phase_ = PointPhase::Returning;
            phase_start_s_ = t_s;
            answered_ = aim_;
            hand_back_ = false;
            last_pointing_s_.reset();
            return {PointStep::Kind::Return, {}, return_pose_};
        }
        return hold;
    case PointPhase::Returning:
        if (pick && !same_as(*pick, *answered_)) return turn_to(t_s, *pick);
        if (arrived(return_pose_.pan_deg, return_pose_.tilt_deg, head) ||
            t_s - phase_start_s_ >= config_.travel_timeout_s) {
            phase_ = PointPhase::Following;
            return {};
        }
        return hold;
    }
    return hold;
}

}  // namespace gc::headctl
