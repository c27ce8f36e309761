#include "measure/edge_search.hpp"

namespace gc {

double sample_bilinear(const cv::Mat1b& map, double x, double y) {
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int xx, int yy) -> double {
        if (xx < 0 || yy < 0 || xx >= map.cols || yy >= map.rows) return 0.0;
        return map(yy, xx);
    };
    const double top = at(x0, y0) * (1.0 - fx) + at(x0 + 1, y0) * fx;
    const double bottom = at(x0, y0 + 1) * (1.0 - fx) + at(x0 + 1, y0 + 1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}

bool find_skin_edge_precise(const cv::Mat1b& map, cv::Point2d p, cv::Point2d n, double half,
                            double step, double& offset) {
    if (!(step > 0.0) || !(half > 0.0)) return false;
    const int count = static_cast<int>(std::floor(2.0 * half / step));
    double prev = -1.0;
    for (int k = 0; k <= count; ++k) {
        const double t = -half + k * step;
        const double v = sample_bilinear(map, p.x + t * n.x, p.y + t * n.y);
        if (prev >= kSkinEdgeLevel && v < kSkinEdgeLevel) {
            offset = t - step + step * (prev - kSkinEdgeLevel) / (prev - v);
            return true;
        }
        prev = v;
    }
    return false;
}

}  // namespace gc
