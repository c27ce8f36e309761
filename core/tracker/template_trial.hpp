// A re-captured hand template on trial beside the one being tracked. A capture of the same
// quality as the template cannot be ranked by how it was captured, so the image decides:
// the candidate follows the filter's motion, is refined each frame, and after a few frames
// replaces the template if more of its outline agrees with the edges seen. A template
// merged with a static skin-coloured object loses edges as the hand moves off the object;
// a capture of the hand alone does not.
#pragma once

#include "common/types.hpp"
#include "contour/hand_template.hpp"
#include "skin/skin_model.hpp"

#include <opencv2/core.hpp>

#include <limits>

namespace gc {

// `s` moved by the similarity motion (translation, rotation, scale) that took `from` to `to`.
HandState moved_along(const HandState& s, const HandState& from, const HandState& to);

class TemplateTrial {
public:
    static constexpr int kFrames = 8;        // frames the two are compared over
    static constexpr double kMargin = 0.05;  // mean agreement the candidate must gain
    // Agreement gained on every frame that no doubt about the moment (weak edges) outweighs.
    static constexpr double kClearMargin = 0.25;

    enum class Verdict { Running, Kept, Replaced };

    // `at`: the candidate's state in the frame it was captured from.
    TemplateTrial(HandTemplate candidate, SkinModel skin, const HandState& at);

    // One frame: the tracked template moved from `before` to `after` and its refinement
    // agreed with the image by `current_agreement` (FitResult::agreement). The candidate
    // is moved the same way and refined on `membership` (and `bgr`, for the colour edge).
    Verdict step(const cv::Mat1b& membership, const cv::Mat& bgr, const HandState& before, const HandState& after,
                 double current_agreement);

    // Frames stepped so far, and whether on every one of them the candidate's outline has
    // agreed with the image by at least kClearMargin more than the tracked template's.
    int frames() const { return frames_; }
    bool clearly_better() const { return frames_ > 0 && least_gain_ >= kClearMargin; }

    HandTemplate& candidate() { return candidate_; }
    const HandTemplate& candidate() const { return candidate_; }
    const SkinModel& skin() const { return skin_; }
    const HandState& state() const { return state_; }

private:
    HandTemplate candidate_;
    SkinModel skin_;
    HandState state_;
    double agreement_ = 0.0;          // the candidate's, summed over the frames so far
    double current_agreement_ = 0.0;  // the tracked template's, over the same frames
    int frames_ = 0;
    double least_gain_ = std::numeric_limits<double>::infinity();  // smallest per-frame gain so far
};

}  // namespace gc
