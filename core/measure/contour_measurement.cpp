#include "measure/contour_measurement.hpp"

#include "measure/edge_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

ContourMeasurement::ContourMeasurement(const ObservationParams& params) : p_(params)
{
    if (p_.half_window < 2 || p_.half_window > 64 || !(p_.sigma > 0.0) || !(p_.effective_normals > 0.0) ||
        p_.min_grey_step < 0 || p_.min_grey_step > 255)
        throw std::invalid_argument("ContourMeasurement: need 2 <= half_window <= 64, "
                                    "sigma > 0, effective_normals > 0 and "
                                    "0 <= min_grey_step <= 255");
    const double mu2 = double(p_.half_window) * p_.half_window;
    log_scale_ = p_.effective_normals * mu2 / (2.0 * p_.sigma * p_.sigma);
    cap2_ = static_cast<float>(mu2);
}

double ContourMeasurement::normal_likelihood(double misfit) const
{
    const double mu2 = double(p_.half_window) * p_.half_window;
    return std::exp(-mu2 * misfit / (2.0 * p_.sigma * p_.sigma));
}

namespace {

// Calls visit(i, px, py, nx, ny) for each measurement normal placed by `state` (contour
// point and unit outward normal in image pixels) until it returns false.
template <typename Visit>
void for_each_normal(const HandTemplate& shape, const HandState& state, Visit&& visit)
{
    check_squash(state, "ContourMeasurement");
    const float c = static_cast<float>(std::cos(state.rotation));
    const float s = static_cast<float>(std::sin(state.rotation));
    const float k = static_cast<float>(state.scale);
    const float a = static_cast<float>(state.squash);
    const float tx = static_cast<float>(state.x), ty = static_cast<float>(state.y);
    const float cs = c * k, ss = s * k;
    const std::size_t m = shape.points.size();
    if (a == 1.0f) {  // unsquashed (a new or unclean template): the normals stay unit
        for (std::size_t i = 0; i < m; ++i) {
            const cv::Point2f& u = shape.points[i];
            const cv::Point2f& n = shape.normals[i];
            if (!visit(i, tx + cs * u.x - ss * u.y, ty + ss * u.x + cs * u.y, c * n.x - s * n.y, s * n.x + c * n.y))
                return;
        }
        return;
    }
    // Squashed: the normals change length and need normalising. Done a block at a time
    // ahead of the search, where the loop has no branch and vectorises (sqrt included).
    constexpr std::size_t kBlock = 64;
    float nxs[kBlock], nys[kBlock];
    const float inv_a = 1.0f / a;
    for (std::size_t first = 0; first < m; first += kBlock) {
        const std::size_t count = std::min(kBlock, m - first);
        const cv::Point2f* n = shape.normals.data() + first;
        for (std::size_t j = 0; j < count; ++j) {
            const float nx = (c * n[j].x - s * n[j].y) * inv_a, ny = s * n[j].x + c * n[j].y;
            const float inv_len = 1.0f / std::sqrt(nx * nx + ny * ny);
            nxs[j] = nx * inv_len;
            nys[j] = ny * inv_len;
        }
        for (std::size_t j = 0; j < count; ++j) {
            const cv::Point2f& u = shape.points[first + j];
            if (!visit(first + j, tx + a * (cs * u.x - ss * u.y), ty + ss * u.x + cs * u.y, nxs[j], nys[j])) return;
        }
    }
}

bool is_skin_at(const cv::Mat1b& map, float x, float y)
{
    const int ix = cvRound(x), iy = cvRound(y);
    return ix >= 0 && iy >= 0 && ix < map.cols && iy < map.rows && map(iy, ix) >= kSkinEdgeLevel;
}

}  // namespace

double ContourMeasurement::misfit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& state,
                                  double give_up) const
{
    return misfit(membership, cv::Mat1b(), shape, state, give_up);
}

double ContourMeasurement::misfit(const cv::Mat1b& membership, const cv::Mat1b& grey, const HandTemplate& shape,
                                  const HandState& state, double give_up) const
{
    const float limit = static_cast<float>(std::min(give_up, 2.0)) * cap2_;
    const bool use_grey = p_.min_grey_step > 0 && !grey.empty() && grey.size() == membership.size();
    float total = 0.0f;
    for_each_normal(shape, state, [&](std::size_t i, float px, float py, float nx, float ny) {
        float d = 0.0f;
        bool skin_beyond = false;
        float d2 = cap2_;
        if (find_skin_edge_fast(membership, px, py, nx, ny, p_.half_window, d, &skin_beyond) ||
            (use_grey && skin_beyond && find_grey_step_fast(grey, px, py, nx, ny, p_.half_window, p_.min_grey_step, d)))
            d2 = std::min(d * d, cap2_);
        total += shape.weights[i] * d2;
        return total <= limit;
    });
    return std::clamp(total / cap2_, 0.0f, 1.0f);
}

double ContourMeasurement::judged_misfit(const cv::Mat1b& membership, const HandTemplate& shape, const HandState& state,
                                         double& judged) const
{
    double total = 0.0, weight = 0.0;
    for_each_normal(shape, state, [&](std::size_t i, float px, float py, float nx, float ny) {
        float d = 0.0f;
        double d2 = cap2_;
        if (find_skin_edge_fast(membership, px, py, nx, ny, p_.half_window, d))
            d2 = std::min(double(d) * d, double(cap2_));
        else if (is_skin_at(membership, px, py))
            return true;  // skin on both sides: no evidence either way
        total += shape.weights[i] * d2;
        weight += shape.weights[i];
        return true;
    });
    judged = weight;
    return weight > 0.0 ? std::clamp(total / (weight * cap2_), 0.0, 1.0) : 1.0;
}

}  // namespace gc
