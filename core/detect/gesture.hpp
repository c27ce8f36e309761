// The hand's gesture from its 21 landmarks: which of the four fingers are extended.
#pragma once

#include "common/types.hpp"
#include "detect/hand_landmarks.hpp"

#include <array>

namespace gc {

// Index, middle, ring, pinky: extended when the fingertip lies clearly farther from the
// wrist than the finger's middle joint (PIP). A ratio of distances, so it holds at any
// scale and in-plane rotation; a curled finger brings its tip back towards the palm.
std::array<bool, 4> extended_fingers(const HandKeyPoints& hand);

// Pointing: the index finger alone extended; Open: all four fingers; Fist: none; Other:
// any other combination. The thumb is left out: it takes every pose in all of them.
Gesture classify_gesture(const HandKeyPoints& hand);

}  // namespace gc
