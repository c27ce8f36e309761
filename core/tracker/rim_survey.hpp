// What lies just inside and just outside a placed contour: the checks that tell whether
// the hand is still under it when its edges no longer fit (in front of a face, a
// skin-coloured object, or the image border).
#pragma once

#include "background/static_background.hpp"
#include "common/types.hpp"
#include "contour/hand_template.hpp"

#include <opencv2/core.hpp>

namespace gc {

// Counts over the outline points of a contour, 2.5 px in and out along the normals.
struct RimSurvey {
    int points = 0;
    bool in_view = true;  // every inner point inside the frame
    int skin = 0, finger = 0, finger_skin = 0;
    int moved = 0, scene = 0;  // inner points known to differ from the scene / the scene
    int scene_outside = 0;     // outer points that match the scene (Scene or Unsure)
};

// Surveys the outline of `t` placed at `s` on the skin `membership` map; `scene` is the
// learnt static scene (nullptr while none is known), compared against `bgr`.
RimSurvey survey_rim(const HandTemplate& t, const HandState& s, const cv::Mat1b& membership,
                     const StaticBackground* scene, const cv::Mat& bgr);

// Whether the inner rim's skin says the hand is under the contour.
bool rim_is_skin(const RimSurvey& rim);

// Whether the contour outlines something that moved in front of the learnt static scene,
// with skin on at least half its rim (a hand, not a sleeve).
bool outlines_foreground(const RimSurvey& rim);

// Inner rim share of the static scene above which a contour holds some of it (a hand
// alone shows less), and above which it lies on the scene rather than on the hand.
inline constexpr double kMergedSceneFraction = 0.15;
inline constexpr double kOnSceneFraction = 0.5;

}  // namespace gc
