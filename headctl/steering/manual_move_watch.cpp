#include "headctl/steering/manual_move_watch.hpp"

#include <cmath>

namespace gc::headctl {

namespace {

double axis_angle(const HeadPose& pose, Axis axis) { return axis == Axis::Pan ? pose.pan_deg : pose.tilt_deg; }

}  // namespace

void ManualMoveWatch::release(AxisWatch& axis, double t_s, bool driven, std::optional<double> destination)
{
    axis.held = false;
    axis.driven = driven;
    axis.commanded_s = t_s;
    axis.destination_deg = destination;
    axis.motion_began_s.reset();
    axis.rest_began_s.reset();
    axis.stirring = false;
}

// Whether a released axis has come to rest where the link's commands leave it.
bool ManualMoveWatch::may_hold(const AxisWatch& axis, double angle_deg, bool moving, double t_s) const
{
    if (axis.driven || moving || t_s - axis.commanded_s < config_.settle_s) return false;
    return !axis.destination_deg || std::abs(angle_deg - *axis.destination_deg) <= config_.arrival_tolerance_deg ||
           t_s - axis.commanded_s >= config_.arrival_timeout_s;
}

void ManualMoveWatch::commanded(const HeadCommand& command, double t_s)
{
    for (std::size_t i = 0; i < kAxes.size(); ++i) {
        AxisWatch& axis = axes_[i];
        switch (command.kind) {
        case CommandKind::Velocity:
            if (!command.values.has(kAxes[i])) break;
            // Holding still an axis that is held changes nothing; any other velocity moves it.
            if (command.values.get(kAxes[i]) != 0.0)
                release(axis, t_s, true);
            else if (!axis.held)
                release(axis, t_s, false);
            break;
        case CommandKind::Absolute:
            if (command.values.has(kAxes[i])) release(axis, t_s, false, command.values.get(kAxes[i]));
            break;
        case CommandKind::Relative:
            if (command.values.has(kAxes[i])) release(axis, t_s, false);
            break;
        case CommandKind::Home:
            release(axis, t_s, false, home_value(kAxes[i]));
            break;
        case CommandKind::Stop:
        case CommandKind::RecallPreset:
            release(axis, t_s, false);
            break;
        case CommandKind::SavePreset:
            break;
        }
    }
}

// A held axis's reported motion: when it began (after settle_s reported at rest, or first
// since held), and whether this sample, still within the tolerance, is in its first settle_s.
void ManualMoveWatch::follow_motion(AxisWatch& axis, bool moving, bool away, double t_s) const
{
    if (moving) {
        const bool rested = axis.rest_began_s && t_s - *axis.rest_began_s >= config_.settle_s;
        if (!axis.motion_began_s || rested || t_s < *axis.motion_began_s) axis.motion_began_s = t_s;
        axis.rest_began_s.reset();
    } else if (!axis.rest_began_s) {
        axis.rest_began_s = t_s;
    }
    axis.stirring = moving && !away && t_s - *axis.motion_began_s < config_.settle_s;
}

bool ManualMoveWatch::moved_by_someone_else(const HeadState& state, double t_s)
{
    bool moved = false;
    for (std::size_t i = 0; i < kAxes.size(); ++i) {
        AxisWatch& axis = axes_[i];
        const double angle = axis_angle(state.pose, kAxes[i]);
        const bool moving = state.moving_axis(kAxes[i]);
        if (axis.held) {
            const bool away = std::abs(angle - axis.rest_deg) > config_.tolerance_deg;
            moved = moved || away;
            follow_motion(axis, moving, away, t_s);
        } else if (may_hold(axis, angle, moving, t_s)) {
            axis.held = true;
            axis.rest_deg = angle;
            axis.motion_began_s.reset();
            axis.rest_began_s = t_s;
        }
    }
    return moved;
}

bool ManualMoveWatch::stirring(Axis axis) const
{
    for (std::size_t i = 0; i < kAxes.size(); ++i)
        if (kAxes[i] == axis) return axes_[i].stirring;  // cleared whenever the axis is released
    return false;
}

void ManualMoveWatch::reset()
{
    for (AxisWatch& axis : axes_) axis = AxisWatch{};
}

}  // namespace gc::headctl
