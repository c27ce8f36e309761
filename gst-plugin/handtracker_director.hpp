// handtracker's director: a second PTZ camera that frames what a held pointing picked. Its URI
// is checked at start; the camera is built at the first tracked frame, from the calibration's
// director_* keys (or the default mount), and told each frame what to frame.
#pragma once

#include "handtracker_state.hpp"

namespace gc::gst {

// Checks the director URI and its parameters (an error on the bus naming it when either is
// wrong); true when there is none. Nothing connects yet.
bool prepare_director(GstHandTracker* self, const TrackerSettings& settings);

// After a tracked frame: the director frames the picked target, or goes home once it is
// released, and a `director` element message (event frame with pan-deg, tilt-deg and zoom,
// home, manual-pause or resume) says so. Never waits on the network.
void direct_camera(GstHandTracker* self, const TrackerSettings& settings, const FrameResult& result);

}  // namespace gc::gst
