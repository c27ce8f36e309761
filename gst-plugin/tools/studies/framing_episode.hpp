// One episode of the framing study: a fresh simulated head, two live rendered eyes with the
// hand held still, handtracker steer=fixate, and what frames the target scored against the
// rendered truth: the attended crop (the hand aimed so that its target lies in the left view),
// or a second simulated head as the director (the hand aimed to one side, its target out of
// the stereo views).
#pragma once

#include <opencv2/core.hpp>

#include <optional>
#include <string>

namespace gc::study {

// With a director: where the finger points from the palm (degrees right of straight ahead,
// up), across the views to either side, so that the target lies outside them.
inline constexpr double kSideDirections[6][2] = {{55, 8}, {-55, 8}, {45, -8}, {-45, -8}, {65, 0}, {-65, 0}};

struct Episode {
    unsigned seed = 1;
    double target_distance_mm = 2000.0;
    double region_mm = 500.0;
    int direction = 0;  // which of the study's pointing directions (any integer)
    double seconds = 6.0;
    bool director = false;  // a director camera frames the target instead of the attended crop
};

struct EpisodeResult {
    std::string aim;                            // where the hand points, as handscenesrc's `aim`
    std::string error;                          // empty when the pipeline ran to its end
    int frames = 0, tracked = 0, pointing = 0;  // stereo pairs processed, tracked, with a 3D ray
    bool picked = false;
    double pick_s = 0.0;                   // the pick's time since the first frame
    std::optional<double> framed_after_s;  // from the pick to framed for good; nullopt: not framed
    // On the last frame: the true target's centre in the crop or the director's picture
    // (fractions of its width and height) and the region's width over the picture's.
    cv::Vec3d last_placement{-1.0, -1.0, 0.0};
    // The picked target from the true one (right, down), seen from the left eye or the director.
    cv::Vec2d pick_error_deg;
};

EpisodeResult run_episode(const Episode& episode);

}  // namespace gc::study
