#include "tracker/template_trial.hpp"

#include "measure/contour_fit.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gc {

HandState moved_along(const HandState& s, const HandState& from, const HandState& to)
{
    const double k = to.scale / from.scale, dr = to.rotation - from.rotation;
    const double vx = s.x - from.x, vy = s.y - from.y;
    const double c = std::cos(dr), sn = std::sin(dr);
    return HandState{to.x + k * (c * vx - sn * vy), to.y + k * (sn * vx + c * vy), s.rotation + dr, s.scale * k,
                     s.squash};
}

TemplateTrial::TemplateTrial(HandTemplate candidate, SkinModel skin, const HandState& at)
    : candidate_(std::move(candidate)), skin_(std::move(skin)), state_(at)
{
}

TemplateTrial::Verdict TemplateTrial::step(const cv::Mat1b& membership, const cv::Mat& bgr, const HandState& before,
                                           const HandState& after, double current_agreement)
{
    const HandState guess = moved_along(state_, before, after);
    const FitResult fit = refine_fit(membership, candidate_, guess, FitParams{}, bgr);
    state_ = fit.converged ? fit.state : guess;
    const double agreement = fit.converged ? fit.agreement : 0.0;
    least_gain_ = std::min(least_gain_, agreement - current_agreement);
    agreement_ += agreement;
    current_agreement_ += current_agreement;
    if (++frames_ < kFrames) return Verdict::Running;
    return agreement_ > current_agreement_ + kMargin * kFrames ? Verdict::Replaced : Verdict::Kept;
}

}  // namespace gc
