#include "headctl/axes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace gc::headctl {

namespace {
constexpr std::array<std::string_view, kAxisCount> kNames{"pan", "tilt", "verge_l", "verge_r", "zoom"};
// The pose's field of each axis, in the same order.
constexpr std::array<double HeadPose::*, kAxisCount> kFields{
    &HeadPose::pan_deg, &HeadPose::tilt_deg, &HeadPose::verge_left_deg, &HeadPose::verge_right_deg, &HeadPose::zoom};
}  // namespace

std::string_view axis_name(Axis axis) { return kNames[static_cast<std::size_t>(axis)]; }

double home_value(Axis axis) { return axis == Axis::Zoom ? 1.0 : 0.0; }

std::optional<Axis> axis_from_name(std::string_view name)
{
    for (Axis a : kAllAxes) {
        if (axis_name(a) == name) return a;
    }
    return std::nullopt;
}

double axis_value(const HeadPose& pose, Axis axis) { return pose.*kFields[static_cast<std::size_t>(axis)]; }

void set_axis_value(HeadPose& pose, Axis axis, double deg) { pose.*kFields[static_cast<std::size_t>(axis)] = deg; }

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
