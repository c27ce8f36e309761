// The director: a second PTZ camera, on any backend, that frames what a held pointing picked
// while the stereo head keeps the speaker's hand in view. It turns and zooms so that the
// target sits in the middle of its picture with the region across its width, and goes back
// to its home (or a preset) when the target is released. Plain C++; the network traffic is
// on its head client's thread, so no call here waits on it.
#pragma once

#include "headctl/head_client.hpp"
#include "headctl/steering/manual_move_watch.hpp"
#include "stereo/director_mount.hpp"

#include <opencv2/core.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace gc::headctl {

// What show() did: framed a target, sent the camera home (or to its preset), noticed that
// someone else moved it (it is left alone for manual_pause_s) or ended that pause.
enum class DirectorEvent { Frame, Home, ManualPause, Resume };
std::string_view to_string(DirectorEvent event);

struct DirectorCameraConfig {
    std::string uri;  // any head URI (headctl/uri.hpp)
    std::string token;
    DirectorMount mount;       // where it stands in the stereo head's frame, its lens at zoom 1
    double region_mm = 500.0;  // the width framed around a target
    // Where it goes when the target is released: this preset, or home (pan 0, tilt 0, widest).
    std::optional<int> home_preset;
    // After someone else moved it (headctl, its own remote), it is left alone this long
    // (seconds); a target held when the pause ends is framed then. 0: never pause.
    double manual_pause_s = 10.0;
    ManualMoveConfig manual;
    std::function<Timestamp()> clock;  // steady_clock when empty
    // Called on the client's thread at each connection change; must not block.
    std::function<void(ConnectionState, const std::string& error)> on_state_change;
    // Called on the thread of show() with each command handed to the client; must not block.
    std::function<void(const HeadCommand&)> on_command;

    void validate() const;  // throws std::invalid_argument naming the field
};

class DirectorCamera {
public:
    // Validates the configuration and the URI (std::invalid_argument) and starts connecting.
    explicit DirectorCamera(DirectorCameraConfig config);
    ~DirectorCamera();
    DirectorCamera(const DirectorCamera&) = delete;
    DirectorCamera& operator=(const DirectorCamera&) = delete;

    // Called every frame with the picked target (head frame, millimetres) or nullopt. A new
    // target is framed once the camera has answered (its zoom range known); a released one
    // sends the camera home. The same target again sends nothing, and nothing is sent while
    // the camera is paused after someone else moved it. Says what it did, if anything.
    std::optional<DirectorEvent> show(const std::optional<cv::Vec3d>& target);
    // The width framed around a target from the next target on (std::invalid_argument if not > 0).
    void set_region(double region_mm);
    // The pause after a manual move, from the next move on (std::invalid_argument if < 0).
    void set_manual_pause(double seconds);

    // The pose the camera was last sent to frame a target; nullopt before or after.
    std::optional<HeadPose> aim() const;
    bool paused() const;
    const HeadClient& client() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc::headctl
