// The observation model p(Z | X) of one hypothesis: the template's measurement normals are
// placed by the state, the skin edge is searched along each (interior to exterior), and the
// finger-weighted, capped squared distances are combined:
//
//   q(X)        = sum_m w_m min(d_m^2, mu^2) / mu^2            (in [0, 1]; sum w_m = 1)
//   p(Z | X)    = exp(-M_eff mu^2 q / (2 sigma^2))
//
// mu is the half window (no edge found costs as much as an edge at the window's end) and
// M_eff the number of effectively independent normals (neighbouring normals see the same
// blur and shading, so they are not M independent measurements). Where a normal runs from
// skin into skin (the hand in front of a face) and a grey map is given, d_m is the offset
// of the strongest grey-level step instead. See docs/tracker.md.
#pragma once

#include "common/types.hpp"
#include "contour/hand_template.hpp"

#include <opencv2/core.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace gc {

struct ObservationParams {
    int half_window = 8;              // mu, pixels: the search runs over [-mu, +mu]
    double sigma = 2.0;               // pixels: expected edge localisation error
    double effective_normals = 12.0;  // M_eff
    // Grey levels between the samples either side of a skin-against-skin edge: about 5
    // sigma of the difference of two pixels' sensor noise. 0: skin edges only.
    int min_grey_step = 16;
};

class ContourMeasurement {
public:
    // Throws std::invalid_argument on invalid parameters.
    explicit ContourMeasurement(const ObservationParams& params = {});

    const ObservationParams& params() const { return p_; }

    // q(X) of the template placed by `state` on a membership map (SkinModel::membership).
    // No allocation: safe to call for every particle. The sum stops early once it exceeds
    // `give_up` (then some value > give_up is returned): a hypothesis that much worse than
    // the best one so far has a negligible weight anyway.
    double misfit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& state,
                  double give_up = 2.0) const;
    // The same with the grey map of the frame (CV_8UC1, the membership map's size, valid
    // wherever the membership is; kSceneGreyLevel where the learnt static scene shows, see
    // find_grey_step_fast): normals from skin into skin are measured on it. An empty or
    // differently sized `grey` is not used.
    double misfit(const cv::Mat1b& membership, const cv::Mat1b& grey, const HandTemplate& shape, const HandState& state,
                  double give_up = 2.0) const;

    // q(X) over the normals that can judge the hypothesis: a normal whose contour point and
    // everything outward along it are skin (no fall in the window) is skin against skin,
    // the hand in front of a face or a skin-coloured object, and says nothing about where
    // the hand's edge is. Weights renormalised over the judging normals; `judged` gets
    // their share of the weight (0 when none judges, then the misfit is 1).
    double judged_misfit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& state,
                         double& judged) const;

    // The misfit margin over the best hypothesis beyond which a weight is below e^-12 of
    // the best one: a safe give_up bound for weighting.
    double negligible_margin() const { return 12.0 / log_scale_; }

    double log_likelihood(double misfit) const { return -log_scale_ * misfit; }
    // The per-normal (geometric-mean) likelihood exp(-mu^2 q / (2 sigma^2)): comparable
    // across frames and template sizes; confidence and loss detection use this.
    double normal_likelihood(double misfit) const;

private:
    ObservationParams p_;
    double log_scale_;
    float cap2_;
};

// Throws std::invalid_argument, naming `who`, unless the state's squash is finite and > 0:
// the measurement and the fit divide by it.
inline void check_squash(const HandState& s, const char* who)
{
    if (!(std::isfinite(s.squash) && s.squash > 0.0))
        throw std::invalid_argument(std::string(who) + ": the state's squash must be finite and > 0");
}

// Where a state puts a template point: diag(squash, 1) s R(r) u + t (image axes, y down).
inline cv::Point2d place(const HandState& s, const cv::Point2f& u)
{
    const double c = std::cos(s.rotation) * s.scale, sn = std::sin(s.rotation) * s.scale;
    // (squash * c) first: at squash 1 the sums round exactly as a similarity's.
    return {s.x + (s.squash * c) * u.x - (s.squash * sn) * u.y, s.y + sn * u.x + c * u.y};
}

// Where a state turns a template normal: the inverse transpose of place()'s linear part,
// normalised (a squash tilts normals towards the horizontal).
inline cv::Point2d place_normal(const HandState& s, const cv::Point2f& n)
{
    const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
    if (s.squash == 1.0) return {c * n.x - sn * n.y, sn * n.x + c * n.y};
    const double nx = (c * n.x - sn * n.y) / s.squash, ny = sn * n.x + c * n.y;
    const double len = std::sqrt(nx * nx + ny * ny);
    return {nx / len, ny / len};
}

}  // namespace gc
