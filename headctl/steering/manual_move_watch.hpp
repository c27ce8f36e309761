// Tells when someone else moved the head: the link reports each command it sends and each
// state the head reports, and the watch says when pan or tilt left the place where the
// link's own commands hold it still. Plain C++, no clock of its own (docs/steering.md).
#pragma once

#include "headctl/head_backend.hpp"

#include <array>
#include <limits>
#include <optional>

namespace gc::headctl {

struct ManualMoveConfig {
    double tolerance_deg = 0.3;  // pose readings wander this much at rest without anyone moving the head
    double settle_s = 0.25;      // after a command, the head is let come to rest this long before it is held
    // After a command that names where an axis goes (absolute, home), the axis is held only
    // once it rests within arrival_tolerance_deg of there, or arrival_timeout_s after the
    // command: over a slow link (ONVIF over HTTP, Pelco-D at 2400 baud, VISCA's inferred
    // motion) the head still reports its old pose, at rest, for a while after the command.
    double arrival_tolerance_deg = 1.0;
    double arrival_timeout_s = 5.0;
};

class ManualMoveWatch {
public:
    explicit ManualMoveWatch(const ManualMoveConfig& config = {}) : config_(config) {}

    // The link handed `command` to the head at `t_s` (seconds, the states' clock).
    void commanded(const HeadCommand& command, double t_s);
    // A state the head reported at `t_s`: true when pan or tilt moved away from where the
    // link's commands hold it at rest (someone else moved the head).
    bool moved_by_someone_else(const HeadState& state, double t_s);
    // Whether the last state showed the held `axis` (pan or tilt) moving, still within the
    // tolerance, less than settle_s after its motion began: perhaps the first samples of
    // someone else's move. Its picture may already have shifted; a velocity for the axis
    // sent then would release it and cancel the move before the next sample shows it. A
    // motion begins after the axis has been reported at rest for settle_s (flags that come
    // and go on a reading that wobbles do not begin it again), and one longer than settle_s
    // is taken for the reading's noise.
    bool stirring(Axis axis) const;
    // Forgets where the axes were held: they are held again once at rest.
    void reset();

private:
    // Free: moving on a command, or settling after one; Held: at rest at `rest_deg` with
    // nothing of the link's to move it.
    struct AxisWatch {
        bool held = false;
        bool driven = false;  // a velocity other than 0 is in force
        double rest_deg = 0.0;
        double commanded_s = -std::numeric_limits<double>::infinity();
        std::optional<double> destination_deg;  // where the last command sends it, when it says
        std::optional<double> motion_began_s;   // while held: when the reported motion began...
        std::optional<double> rest_began_s;     // ...and since when it is reported at rest
        bool stirring = false;
    };
    static constexpr std::array<Axis, 2> kAxes{Axis::Pan, Axis::Tilt};

    void release(AxisWatch& axis, double t_s, bool driven, std::optional<double> destination = std::nullopt);
    bool may_hold(const AxisWatch& axis, double angle_deg, bool moving, double t_s) const;
    void follow_motion(AxisWatch& axis, bool moving, bool away, double t_s) const;

    ManualMoveConfig config_;
    std::array<AxisWatch, 2> axes_{};
};

}  // namespace gc::headctl
