#include "measure/contour_measurement.hpp"

#include "measure/edge_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

ContourMeasurement::ContourMeasurement(const ObservationParams& params) : p_(params) {
    if (p_.half_window < 2 || p_.half_window > 64 || !(p_.sigma > 0.0) ||
        !(p_.effective_normals > 0.0))
        throw std::invalid_argument("ContourMeasurement: need 2 <= half_window <= 64, "
                                    "sigma > 0 and effective_normals > 0");
    const double mu2 = double(p_.half_window) * p_.half_window;
    log_scale_ = p_.effective_normals * mu2 / (2.0 * p_.sigma * p_.sigma);
    cap2_ = static_cast<float>(mu2);
}

double ContourMeasurement::normal_likelihood(double misfit) const {
    const double mu2 = double(p_.half_window) * p_.half_window;
    return std::exp(-mu2 * misfit / (2.0 * p_.sigma * p_.sigma));
}

double ContourMeasurement::misfit(const cv::Mat1b& membership, const HandTemplate& shape,
                                  const HandState& state, double give_up) const {
    const float c = static_cast<float>(std::cos(state.rotation));
    const float s = static_cast<float>(std::sin(state.rotation));
    const float k = static_cast<float>(state.scale);
    const float tx = static_cast<float>(state.x), ty = static_cast<float>(state.y);
    const float cs = c * k, ss = s * k;
    const std::size_t m = shape.points.size();
    const float limit = static_cast<float>(std::min(give_up, 2.0)) * cap2_;
    float total = 0.0f;
    for (std::size_t i = 0; i < m; ++i) {
        const cv::Point2f& u = shape.points[i];
        const cv::Point2f& n = shape.normals[i];
        const float px = tx + cs * u.x - ss * u.y;
        const float py = ty + ss * u.x + cs * u.y;
        const float nx = c * n.x - s * n.y;
        const float ny = s * n.x + c * n.y;
        float d = 0.0f;
        const float d2 = find_skin_edge_fast(membership, px, py, nx, ny, p_.half_window, d)
                             ? std::min(d * d, cap2_)
                             : cap2_;
        total += shape.weights[i] * d2;
        if (total > limit) break;
    }
    return std::clamp(total / cap2_, 0.0f, 1.0f);
}

}  // namespace gc
