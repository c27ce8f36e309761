// The five axes of a head (the neck's pan and tilt, each eye's vergence, the lenses' zoom),
// their wire names, and per-axis value sets.
#pragma once

#include "common/types.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace gc::headctl {

// Angles in degrees, except Zoom: a magnification, 1 being the widest field of view (its
// velocities and accelerations are magnification per second, per second squared).
enum class Axis { Pan = 0, Tilt = 1, VergeLeft = 2, VergeRight = 3, Zoom = 4 };

inline constexpr std::size_t kAxisCount = 5;
inline constexpr std::array<Axis, kAxisCount> kAllAxes{Axis::Pan, Axis::Tilt, Axis::VergeLeft, Axis::VergeRight,
                                                       Axis::Zoom};

// Where HOME puts an axis: 0 degrees, or the widest zoom (1).
double home_value(Axis axis);

// Names used on the wire and on the command line.
std::string_view axis_name(Axis axis);
std::optional<Axis> axis_from_name(std::string_view name);

double axis_value(const HeadPose& pose, Axis axis);
void set_axis_value(HeadPose& pose, Axis axis, double deg);

// A value for some of the axes (a move names only the axes it changes).
class AxisValues {
public:
    bool has(Axis a) const { return values_[index(a)].has_value(); }
    double get(Axis a) const { return values_[index(a)].value(); }
    const std::optional<double>& operator[](Axis a) const { return values_[index(a)]; }
    void set(Axis a, double v) { values_[index(a)] = v; }
    void clear(Axis a) { values_[index(a)].reset(); }
    bool empty() const;
    bool operator==(const AxisValues&) const = default;

private:
    static std::size_t index(Axis a) { return static_cast<std::size_t>(a); }
    std::array<std::optional<double>, kAxisCount> values_{};
};

// One axis's soft limits and motion limits.
struct AxisLimits {
    double min_deg = -90.0;
    double max_deg = 90.0;
    double max_velocity_dps = 90.0;
    double max_acceleration_dps2 = 360.0;
    bool operator==(const AxisLimits&) const = default;
};

// A head without a zoom lens holds its zoom at 1.
inline constexpr AxisLimits kFixedZoomLimits{1.0, 1.0, 1.0, 1.0};

struct HeadLimits {
    std::array<AxisLimits, kAxisCount> axes{AxisLimits{}, AxisLimits{}, AxisLimits{}, AxisLimits{}, kFixedZoomLimits};
    AxisLimits& operator[](Axis a) { return axes[static_cast<std::size_t>(a)]; }
    const AxisLimits& operator[](Axis a) const { return axes[static_cast<std::size_t>(a)]; }
    bool operator==(const HeadLimits&) const = default;
};

// Throws std::invalid_argument naming the axis if a limit is not finite or inconsistent.
void validate(const HeadLimits& limits);

// What a head reports: pose, which axes are moving, and the head's own clock.
struct HeadState {
    std::int64_t server_time_us = 0;
    HeadPose pose;
    std::array<bool, kAxisCount> moving{};
    bool moving_axis(Axis a) const { return moving[static_cast<std::size_t>(a)]; }
};

}  // namespace gc::headctl
