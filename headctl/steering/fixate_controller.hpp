// Keeps a tracked hand in the middle of the view: maps its angular offset from the optical
// axis (and its angular velocity) to pan/tilt velocity commands. The law is in docs/steering.md.
#pragma once

#include "headctl/head_backend.hpp"

#include <optional>

namespace gc::headctl {

struct FixateConfig {
    double dead_band_deg = 1.0;       // offsets inside are left alone...
    double release_band_deg = 2.0;    // ...until they grow beyond this (hysteresis)
    double gain_per_s = 4.0;          // velocity per degree of offset
    double feed_forward = 1.0;        // share of the target's own angular velocity
    double rate_dead_band_dps = 1.0;  // target velocities below this count as noise
    double max_velocity_dps = 60.0;
    double max_acceleration_dps2 = 200.0;  // rate limit of the commanded velocity
    double limit_margin_deg = 1.0;         // stop this far inside the soft limits
    double head_latency_s = 0.05;          // from a command to the head's response
    double hold_s = 2.0;                   // after the hand is lost, hold still this long, then home
    std::optional<int> home_preset;        // home is this preset of the head (else its HOME)
    // Lost for this long (0: never), and not yet home, the lens zooms out towards its widest
    // at widen_rate (magnification per second), so a hand just outside a narrow view shows.
    double widen_after_s = 0.0;
    double widen_rate = 2.0;
    HeadLimits limits;  // the head's soft limits (pan and tilt are used)

    void validate() const;  // throws std::invalid_argument naming the field
};

// What the tracker sees in one frame. Offsets are angles from the optical axis in the
// head's sense: pan > 0 when the hand is right of centre, tilt > 0 when above.
struct FixateObservation {
    bool valid = false;
    double offset_pan_deg = 0.0;
    double offset_tilt_deg = 0.0;
    double rate_pan_dps = 0.0;  // the hand's angular velocity, same axes
    double rate_tilt_dps = 0.0;
};

// Angles of an image point from the principal point (pixels; x right, y down) for focal
// lengths in pixels, in the head's sense (tilt > 0 above the centre).
FixateObservation offset_from_image(double dx_px, double dy_px, double fx_px, double fy_px);

class FixateController {
public:
    explicit FixateController(const FixateConfig& config);

    // One control step dt_s after the previous one, at head pose `head`. Returns the command
    // to send: a pan/tilt velocity, or Home (the home preset's recall when one is set) once
    // the hand has been lost for hold_s; nullopt
    // when there is nothing to send (at home, hand still lost).
    std::optional<HeadCommand> update(const FixateObservation& seen, const HeadPose& head, double dt_s);
    void reset();

private:
    double axis_velocity(std::size_t i, double offset, double rate, double position, const AxisLimits& limits,
                         double dt);

    FixateConfig config_;
    std::array<double, 2> velocity_{};  // last commanded, pan and tilt
    std::array<bool, 2> settled_{};     // inside the dead band
    double lost_s_ = 0.0;
    bool homed_ = false;
    bool widening_ = false;  // the last command drove the zoom out
};

}  // namespace gc::headctl
