#include "measure/contour_fit.hpp"

#include "measure/contour_measurement.hpp"
#include "measure/edge_search.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc {

FitResult refine_fit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& start,
                     const FitParams& params, const cv::Mat& bgr)
{
    check_squash(start, "refine_fit");
    FitResult result;
    result.state = start;
    HandState s = start;
    const std::size_t n = shape.outline.size();
    using Vector5d = Eigen::Matrix<double, 5, 1>;
    using Matrix5d = Eigen::Matrix<double, 5, 5>;
    const int unknowns = params.fit_squash ? 5 : 4;
    for (int it = 0; it < params.iterations; ++it) {
        const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
        const double a0 = s.squash;
        Matrix5d ata = Matrix5d::Zero();
        Vector5d atb = Vector5d::Zero();
        double wsum = 0.0, wd2 = 0.0, found_weight = 0.0, agreeing_weight = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const cv::Point2f& u = shape.outline[i];
            const cv::Point2f& un = shape.outline_normals[i];
            const cv::Point2d p = place(s, u);
            const cv::Point2d nrm = place_normal(s, un);
            double d = 0.0;
            if (!find_skin_edge_precise(membership, p, nrm, params.half_window, params.step, d)) continue;
            if (!bgr.empty()) d = colour_edge_offset(bgr, p, nrm, d);
            const double w = shape.outline_weights[i] / (1.0 + (d / params.robust_scale) * (d / params.robust_scale));
            found_weight += shape.outline_weights[i];
            if (std::abs(d) <= kAgreementPx) agreeing_weight += shape.outline_weights[i];
            // n . (D A u + t) = n . q with q = p + d n and D = diag(squash, 1): linear in
            // (a, b, tx, ty) for a fixed squash; the squash's own step is linearised about
            // its current value (last unknown).
            Vector5d row;
            row << a0 * nrm.x * u.x + nrm.y * u.y, nrm.y * u.x - a0 * nrm.x * u.y, nrm.x, nrm.y,
                nrm.x * s.scale * (c * u.x - sn * u.y);
            const double target = nrm.x * p.x + nrm.y * p.y + d;
            ata += w * row * row.transpose();
            atb += w * target * row;
            wsum += w;
            wd2 += w * d * d;
        }
        result.found_fraction = found_weight;
        result.agreement = agreeing_weight;
        if (found_weight < params.min_found || wsum <= 0.0) return result;
        result.rms_px = std::sqrt(wd2 / wsum);
        Vector5d sol = Vector5d::Zero();
        if (unknowns == 5) {
            // A little damping on the squash: where the outline's horizontal extent is not
            // seen, it stays rather than trading off against the scale.
            ata(4, 4) *= 1.1;
            sol = ata.ldlt().solve(atb);
        } else {
            sol.head<4>() = ata.topLeftCorner<4, 4>().ldlt().solve(atb.head<4>());
        }
        if (!sol.allFinite()) return result;
        const double scale = std::hypot(sol[0], sol[1]);
        // A fit that jumps far from the start has locked onto something else: keep the start.
        if (!(scale > 0.5 * start.scale && scale < 2.0 * start.scale)) return result;
        s.scale = scale;
        // Keep the rotation continuous with the start (atan2 wraps at +-pi).
        s.rotation =
            start.rotation + std::remainder(std::atan2(sol[1], sol[0]) - start.rotation, 2.0 * std::numbers::pi);
        s.x = sol[2];
        s.y = sol[3];
        if (unknowns == 5)
            s.squash = std::clamp(std::clamp(a0 + sol[4], start.squash * (1.0 - params.max_squash_step),
                                             start.squash * (1.0 + params.max_squash_step)),
                                  params.min_squash, params.max_squash);
    }
    result.state = s;
    result.converged = true;
    return result;
}

}  // namespace gc
