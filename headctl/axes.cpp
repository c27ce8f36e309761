#include "headctl/axes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gc::headctl {

namespace {
constexpr std::array<std::string_view, kAxisCount> kNames{"pan", "tilt", "verge_l", "verge_r", "zoom"};
}

std::string_view axis_name(Axis axis) { return kNames[static_cast<std::size_t>(axis)]; }

double home_value(Axis axis) { return axis == Axis::Zoom ? 1.0 : 0.0; }

std::optional<Axis> axis_from_name(std::string_view name)
{
    for (Axis a : kAllAxes) {
        if (axis_name(a) == name) return a;
    }
    return std::nullopt;
}

double axis_value(const HeadPose& pose, Axis axis)
{
    switch (axis) {
    case Axis::Pan:
        return pose.pan_deg;
    case Axis::Tilt:
        return pose.tilt_deg;
    case Axis::VergeLeft:
        return pose.verge_left_deg;
    case Axis::VergeRight:
        return pose.verge_right_deg;
    case Axis::Zoom:
        return pose.zoom;
    }
    return 0.0;
}

void set_axis_value(HeadPose& pose, Axis axis, double deg)
{
    switch (axis) {
    case Axis::Pan:
        pose.pan_deg = deg;
        break;
    case Axis::Tilt:
        pose.tilt_deg = deg;
        break;
    case Axis::VergeLeft:
        pose.verge_left_deg = deg;
        break;
    case Axis::VergeRight:
        pose.verge_right_deg = deg;
        break;
    case Axis::Zoom:
        pose.zoom = deg;
        break;
    }
}

bool AxisValues::empty() const
{
    for (const auto& v : values_) {
        if (v) return false;
    }
    return true;
}

void validate(const HeadLimits& limits)
{
    for (Axis a : kAllAxes) {
        const AxisLimits& l = limits[a];
        const std::string name(axis_name(a));
        if (!std::isfinite(l.min_deg) || !std::isfinite(l.max_deg) || l.min_deg > l.max_deg)
            throw std::invalid_argument("limits of axis " + name + ": min must be <= max, both finite");
        if (l.min_deg > home_value(a) || l.max_deg < home_value(a))
            throw std::invalid_argument("limits of axis " + name + ": the home position " +
                                        (a == Axis::Zoom ? "1" : "0") + " must lie within");
        if (a == Axis::Zoom && l.min_deg < 1.0)
            throw std::invalid_argument("limits of axis zoom: a magnification below 1 does not exist");
        if (!std::isfinite(l.max_velocity_dps) || l.max_velocity_dps <= 0.0)
            throw std::invalid_argument("limits of axis " + name + ": max velocity must be > 0");
        if (!std::isfinite(l.max_acceleration_dps2) || l.max_acceleration_dps2 <= 0.0)
            throw std::invalid_argument("limits of axis " + name + ": max acceleration must be > 0");
    }
}

}  // namespace gc::headctl
