// Discrete-time braking: how fast an axis may go in its next step and still stop in time.
#pragma once

#include <algorithm>
#include <cmath>

namespace gc::headctl {

// The largest speed v for the next step of length dt (position advancing by the mean of
// the current speed and v) after which the axis can still stop, braking at accel, within
// `distance` ahead. speed_towards is the current speed, positive towards that point.
// Unlike the continuous sqrt(2 a d), this leaves no overshoot from the step itself.
inline double braking_speed(double distance, double speed_towards, double accel, double dt)
{
    // v^2 / (2a) <= distance - (speed_towards + v) dt / 2, solved for v.
    const double b = accel * dt;
    const double disc = b * b + 4.0 * (2.0 * accel * std::max(distance, 0.0) - b * speed_towards);
    return disc > 0.0 ? std::max(0.0, 0.5 * (std::sqrt(disc) - b)) : 0.0;
}

}  // namespace gc::headctl
