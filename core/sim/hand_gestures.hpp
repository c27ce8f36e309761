// Where the fingers of the planar hand go in each gesture the renderer shows: pointing (the
// index finger extended, the thumb along it, the other three curled), open (all five
// extended and slightly spread, the thumb out) and fist (all four curled, the thumb across
// them). Model millimetres in the hand's anatomical layout (see hand_model.hpp), before the
// seeded size factor.
#pragma once

#include "common/types.hpp"
#include "sim/hand_model.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace gc::sim {

// A tapered finger drawn along +u from `base` (tip.y == base.y), then turned about its base
// by `spread_deg` (towards the thumb's side for positive angles).
struct StraightFinger {
    cv::Point2d base;
    double base_radius = 0.0;
    cv::Point2d tip;
    double tip_radius = 0.0;
    double spread_deg = 0.0;
};

// A finger curled against the palm, seen as an ellipse.
struct CurledFinger {
    cv::Point2d centre;
    double length = 0.0;
    double width = 0.0;
    double angle_deg = 0.0;
};

struct FingerLayout {
    std::vector<StraightFinger> straight;
    StraightFinger thumb;  // a tapered capsule from base to tip; spread unused
    std::vector<CurledFinger> curled;
};

// The fingers of `shape` in `gesture` (Pointing, Open or Fist): the other gestures take the
// index finger's length and width and the thumb's reach from the shape, so that a seeded
// hand keeps its proportions whatever it does.
FingerLayout finger_layout(const HandShape& shape, Gesture gesture);

// The gesture shown at time t (s): `gesture` throughout when cycle_s is 0, else `gesture` for
// cycle_s seconds, then pointing for cycle_s seconds, and so on.
Gesture gesture_at(Gesture gesture, double cycle_s, double t);

}  // namespace gc::sim
