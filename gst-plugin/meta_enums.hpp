// The tracker's track states and gestures and their counterparts in GstHandPointingMeta: one
// table each, read one way for the meta a buffer carries and the other for the meta written.
#pragma once

#include "common/enum_names.hpp"
#include "common/types.hpp"

#include <gst/gesturecam/gsthandpointingmeta.h>

namespace gc::gst {

inline constexpr EnumNames<TrackState, 3, GstHandPointingState> kMetaStates{{
    {TrackState::Acquiring, GST_HAND_POINTING_STATE_ACQUIRING},
    {TrackState::Tracking, GST_HAND_POINTING_STATE_TRACKING},
    {TrackState::Lost, GST_HAND_POINTING_STATE_LOST},
}};

inline constexpr EnumNames<Gesture, 5, GstHandPointingGesture> kMetaGestures{{
    {Gesture::Unknown, GST_HAND_POINTING_GESTURE_UNKNOWN},
    {Gesture::Pointing, GST_HAND_POINTING_GESTURE_POINTING},
    {Gesture::Open, GST_HAND_POINTING_GESTURE_OPEN},
    {Gesture::Fist, GST_HAND_POINTING_GESTURE_FIST},
    {Gesture::Other, GST_HAND_POINTING_GESTURE_OTHER},
}};

}  // namespace gc::gst
