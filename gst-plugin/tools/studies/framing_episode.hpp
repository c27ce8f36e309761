// One episode of the framing study: a fresh simulated head, two live rendered eyes with the
// hand held still and aimed so that its target lies in view, handtracker steer=fixate
// output=attended, and the attended crop scored against the rendered truth.
#pragma once

#include <opencv2/core.hpp>

#include <optional>
#include <string>

namespace gc::study {

struct Episode {
    unsigned seed = 1;
    double target_distance_mm = 2000.0;
    double region_mm = 500.0;
    int direction = 0;  // which of the study's pointing directions (any integer)
    double seconds = 6.0;
};

struct EpisodeResult {
    std::string aim;    // where the hand points, as handscenesrc's `aim`
    std::string error;  // empty when the pipeline ran to its end
    int frames = 0, tracked = 0, pointing = 0;  // stereo pairs processed, tracked, with a 3D ray
    bool picked = false;
    double pick_s = 0.0;                   // the pick's time since the first frame
    std::optional<double> framed_after_s;  // from the pick to framed for good; nullopt: not framed
    // On the last frame: the true target's centre in the crop (fractions of its width and
    // height) and the region's width over the crop's.
    cv::Vec3d last_placement{-1.0, -1.0, 0.0};
    cv::Vec2d pick_error_deg;  // the picked target from the true one, seen from the left eye (right, down)
};

EpisodeResult run_episode(const Episode& episode);

}  // namespace gc::study
