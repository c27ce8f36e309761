// What steer=point does with one head: keep the speaker's hand in view (the fixate law),
// turn to what a held pointing picked, look there for a while, then come back to the pose
// it left, where the hand was. Plain C++ with times passed in, so it is tested with a fake
// clock; the head link turns its steps into commands (docs/steering.md).
#pragma once

#include "common/types.hpp"

#include <opencv2/core.hpp>

#include <optional>
#include <string_view>

namespace gc::headctl {

struct PointDirectorConfig {
    double look_s = 4.0;            // how long the head stays on a target once it is there
    double same_target_deg = 6.0;   // a pick this close to the target just looked at is that pointing, still held
    double arrive_deg = 0.5;        // pan and tilt this close to where the head was sent: it is there
    double travel_timeout_s = 3.0;  // ...or this long after it was sent (a head that stops short)
    // After a look, the hand tracked without a pointing (or lost again after it was found)
    // this long: the speaker lowered it, and the same target may be picked again.
    double lowered_s = 1.0;

    void validate() const;  // throws std::invalid_argument naming the field
};

// A target a held pointing picked: the point (head frame, mm) and the pan and tilt that
// turn the head's forward axis towards it.
struct PointAim {
    cv::Vec3d target_mm;
    double pan_deg = 0.0;
    double tilt_deg = 0.0;
};

enum class PointPhase { Following, Turning, Looking, Returning };
std::string_view to_string(PointPhase phase);

// What the link does on one frame.
struct PointStep {
    enum class Kind {
        Follow,  // the fixate law keeps the hand in view
        Hold,    // nothing: the head is on its way or looking
        Aim,     // turn to `aim`
        Return,  // go back to `pose`
    };
    Kind kind = Kind::Follow;
    PointAim aim;
    HeadPose pose;
};

class PointDirector {
public:
    explicit PointDirector(const PointDirectorConfig& config = {});

    // One frame at `t_s` (seconds, increasing). `pick`: a target the pointing dwell picked
    // on this very frame (nullopt on the others); `pointing`: the frame has a 3D pointing;
    // `hand_seen`: the tracker has the hand; `head`: the head's pose now.
    PointStep update(double t_s, const std::optional<PointAim>& pick, bool pointing, bool hand_seen,
                     const HeadPose& head);
    PointPhase phase() const { return phase_; }
    void reset();  // back to following, nothing looked at
    // The look time of the looks that start from now on (std::invalid_argument if not > 0).
    void set_look_time(double look_s);

private:
    PointStep turn_to(double t_s, const PointAim& aim);
    bool same_as(const PointAim& a, const PointAim& b) const;
    bool arrived(double pan_deg, double tilt_deg, const HeadPose& head) const;
    void watch_for_lowered_hand(double t_s, bool pointing, bool hand_seen);

    PointDirectorConfig config_;
    PointPhase phase_ = PointPhase::Following;
    PointAim aim_;              // Turning, Looking: where the head was sent
    HeadPose return_pose_;      // where it left the hand
    double phase_start_s_ = 0;  // when the current phase began
    double look_until_s_ = 0;   // Looking
    // The target of the last look, answered; a pick there again is ignored until the hand
    // was lowered.
    std::optional<PointAim> answered_;
    bool hand_back_ = false;  // the hand was seen again since the head came back
    std::optional<double> last_pointing_s_;
};

}  // namespace gc::headctl
