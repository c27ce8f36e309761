// The tracker's estimate read back from a GstHandPointingMeta, in the pixels of the buffer
// that carries it, so the overlay can draw it on any buffer downstream of handtracker.
#pragma once

#include "common/types.hpp"
#include "stereo/pointing.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>
#include <opencv2/core.hpp>

namespace gc::gst {

TrackState track_state(GstHandPointingState s);
Gesture track_gesture(GstHandPointingGesture g);

// One eye's estimate (right: the right view's, when the meta is stereo) mapped from input
// pixels to a buffer of `buffer_size` showing the meta's view rectangle.
EyeEstimate eye_from_meta(const GstHandPointingMeta& meta, bool right, cv::Size buffer_size);

// The 3D pointing of the meta; invalid without GST_HAND_POINTING_FLAG_HAS_3D.
Pointing3D pointing_from_meta(const GstHandPointingMeta& meta);

}  // namespace gc::gst
