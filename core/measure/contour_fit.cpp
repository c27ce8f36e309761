#include "measure/contour_fit.hpp"

#include "measure/contour_measurement.hpp"
#include "measure/edge_search.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <numbers>

namespace gc {

FitResult refine_fit(const cv::Mat1b& membership, const HandTemplate& shape,
                     const HandState& start, const FitParams& params, const cv::Mat& bgr) {
    FitResult result;
    result.state = start;
    HandState s = start;
    const std::size_t n = shape.outline.size();
    for (int it = 0; it < params.iterations; ++it) {
        const double c = std::cos(s.rotation), sn = std::sin(s.rotation);
        Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
        Eigen::Vector4d atb = Eigen::Vector4d::Zero();
        double wsum = 0.0, wd2 = 0.0, found_weight = 0.0, agreeing_weight = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const cv::Point2f& u = shape.outline[i];
            const cv::Point2f& un = shape.outline_normals[i];
            const cv::Point2d p = place(s, u);
            const cv::Point2d nrm(c * un.x - sn * un.y, sn * un.x + c * un.y);
            double d = 0.0;
            if (!find_skin_edge_precise(membership, p, nrm, params.half_window, params.step, d))
                continue;
            if (!bgr.empty()) d = colour_edge_offset(bgr, p, nrm, d);
            const double w = shape.outline_weights[i] /
                             (1.0 + (d / params.robust_scale) * (d / params.robust_scale));
            found_weight += shape.outline_weights[i];
            if (std::abs(d) <= kAgreementPx) agreeing_weight += shape.outline_weights[i];
            // n . (A u + t) = n . q with q = p + d n, linear in (a, b, tx, ty).
            const Eigen::Vector4d row(nrm.x * u.x + nrm.y * u.y, nrm.y * u.x - nrm.x * u.y,
                                      nrm.x, nrm.y);
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
        const Eigen::Vector4d sol = ata.ldlt().solve(atb);
        if (!sol.allFinite()) return result;
        const double scale = std::hypot(sol[0], sol[1]);
        // A fit that jumps far from the start has locked onto something else: keep the start.
        if (!(scale > 0.5 * start.scale && scale < 2.0 * start.scale)) return result;
        s.scale = scale;
        // Keep the rotation continuous with the start (atan2 wraps at +-pi).
        s.rotation = start.rotation + std::remainder(std::atan2(sol[1], sol[0]) - start.rotation,
                                                     2.0 * std::numbers::pi);
        s.x = sol[2];
        s.y = sol[3];
    }
    result.state = s;
    result.converged = true;
    return result;
}

}  // namespace gc
