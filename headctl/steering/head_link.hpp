// The tracker's link to a motorised head: reads the head's pose at each frame's capture time,
// turns the pose change into the camera-motion offset C_t of each eye, and steers the head
// from what the tracker saw. Plain C++ (no GLib), owned by the handtracker element; all
// network traffic happens on the head client's own thread, so no call here waits on it.
#pragma once

#include "headctl/head_client.hpp"
#include "headctl/steering/fixate_controller.hpp"
#include "headctl/steering/manual_move_watch.hpp"
#include "headctl/steering/point_director.hpp"
#include "stereo/calibration.hpp"
#include "stereo/pointing_dwell.hpp"
#include "tracker/pointing_tracker.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace gc::headctl {

// off: only read the pose; fixate: keep the hand in the middle of the left view and verge on
// its depth; point: as fixate, and a pointing held for the dwell time turns the head to
// its target (HeadLinkConfig::target) for the look time, then back to the hand.
enum class SteerMode { Off, Fixate, Point };

std::string_view to_string(SteerMode mode);
std::optional<SteerMode> steer_mode_from_string(std::string_view name);

// What steering did that a person watching the head wants to know.
enum class SteeringEvent {
    Look,         // point: the head turns to a picked target
    Return,       // point: the look is over, the head goes back to where it left the hand
    Follow,       // point: back there, the fixate law follows the hand again
    ManualPause,  // someone else moved the head: steering leaves it alone
    Resume,       // the pause is over: steering starts again from where the head is
};
std::string_view to_string(SteeringEvent event);

// The times of point mode and of the manual pause, changeable while running.
struct SteeringTimes {
    double dwell_s = 1.0;          // point: a pointing held this long picks its target
    double look_s = 4.0;           // point: the head looks at the target this long, then comes back
    double manual_pause_s = 10.0;  // after someone else moved the head, steering waits this long; 0: never
    bool operator==(const SteeringTimes&) const = default;
    void validate() const;  // throws std::invalid_argument naming the field
};

struct HeadLinkConfig {
    std::string uri;  // e.g. tcp://127.0.0.1:5050 (headctl/uri.hpp)
    std::string token;
    SteerMode steer = SteerMode::Fixate;
    gc::TargetPlacement target;        // point mode: where along the ray to look
    double nominal_depth_mm = 1000.0;  // C_t's depth while the 3D position is unknown
    // Fixate-mode pan/tilt law; its limits are replaced by the head's once it reports them.
    headctl::FixateConfig fixate;
    double vergence_gain_per_s = 6.0;  // vergence velocity per degree of error
    double vergence_dead_band_deg = 0.3;
    SteeringTimes times;
    headctl::PointDirectorConfig point;  // its look_s is times.look_s
    headctl::ManualMoveConfig manual;
    std::chrono::milliseconds reconnect_max{500};  // longest wait between connection attempts
    // Views that reach the tracker later than this after their capture do not steer the
    // head (fixate brakes as on a loss): a loop closed over old views turns too far and
    // oscillates. A pipeline that cannot keep up with its cameras would otherwise swing
    // the head from side to side.
    std::chrono::milliseconds max_view_age{250};
    // The clock capture times are on; steady_clock when empty.
    std::function<headctl::Timestamp()> clock;
    // Called on the head client's thread at each connection change; must not block.
    std::function<void(headctl::ConnectionState, const std::string& error)> on_state_change;
    // Called on the thread of end_frame() with each command handed to the head client, so a
    // host can log it with its own logging; must not block.
    std::function<void(const headctl::HeadCommand&)> on_command;
    // Called on the thread of end_frame() at each steering event, with a sentence for a log;
    // must not block.
    std::function<void(SteeringEvent, const std::string& detail)> on_steering;

    void validate() const;  // throws std::invalid_argument naming the field
};

// What the tracker needs before it processes a frame.
struct HeadAtCapture {
    std::optional<HeadPose> pose;  // at the capture time, interpolated; nullopt until known
    ImageMotion left_motion;       // C_t of each eye since the previous frame
    ImageMotion right_motion;
};

class HeadLink {
public:
    // Validates the configuration and the URI (std::invalid_argument) and starts connecting.
    HeadLink(HeadLinkConfig config, StereoCalibration calibration);
    ~HeadLink();
    HeadLink(const HeadLink&) = delete;
    HeadLink& operator=(const HeadLink&) = delete;

    // Before tracking the frame captured at `capture_time` (on the configured clock): the
    // head's pose then and the image motion of each eye since the previous frame, for the
    // hand where the tracker last saw it.
    HeadAtCapture begin_frame(headctl::Timestamp capture_time);
    // After tracking that frame: remembers where the hand is and submits the steering command.
    void end_frame(const FrameResult& result);
    // Changes the steering mode and where point mode's target lies while running (the
    // connection stays); a new mode starts from rest: the fixate law's memory and the last
    // aim are forgotten. Throws std::invalid_argument for a distance that is not > 0.
    void set_steering(SteerMode mode, const gc::TargetPlacement& target);
    // Changes the dwell, look and manual-pause times while running (std::invalid_argument for
    // bad ones); a look under way keeps the time it started with.
    void set_times(const SteeringTimes& times);
    // Where point mode is (Following in the other modes), and whether steering is paused
    // because someone else moved the head.
    headctl::PointPhase point_phase() const;
    bool paused() const;
    // Whether the last frame passed to end_frame was too old to steer from (max_view_age),
    // and how old it was (ms; 0 before any frame).
    bool last_view_stale() const;
    double last_view_age_ms() const;

    headctl::ConnectionState state() const;
    const headctl::HeadClient& client() const;
    headctl::Timestamp now() const;
    const HeadLinkConfig& config() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc::headctl
