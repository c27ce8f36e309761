#include "contour/closed_bspline.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>
#include <string>

namespace gc {

namespace {

// Uniform cubic B-spline basis on one span, t in [0, 1), weights of P[i-1], P[i], P[i+1],
// P[i+2].
void basis(double t, double w[4])
{
    const double t2 = t * t, t3 = t2 * t;
    w[0] = (1.0 - 3.0 * t + 3.0 * t2 - t3) / 6.0;
    w[1] = (4.0 - 6.0 * t2 + 3.0 * t3) / 6.0;
    w[2] = (1.0 + 3.0 * t + 3.0 * t2 - 3.0 * t3) / 6.0;
    w[3] = t3 / 6.0;
}

void basis_derivative(double t, double w[4])
{
    const double t2 = t * t;
    w[0] = (-3.0 + 6.0 * t - 3.0 * t2) / 6.0;
    w[1] = (-12.0 * t + 9.0 * t2) / 6.0;
    w[2] = (3.0 + 6.0 * t - 9.0 * t2) / 6.0;
    w[3] = 3.0 * t2 / 6.0;
}

}  // namespace

ClosedBSpline ClosedBSpline::interpolate(std::span<const cv::Point2d> through)
{
    const int n = static_cast<int>(through.size());
    if (n < 4) throw std::invalid_argument("ClosedBSpline: need at least 4 points, got " + std::to_string(n));
    for (int i = 0; i < n; ++i) {
        const auto& p = through[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw std::invalid_argument("ClosedBSpline: point " + std::to_string(i) + " is not finite");
        const auto& q = through[(i + 1) % n];
        if (std::hypot(p.x - q.x, p.y - q.y) < 1e-9)
            throw std::invalid_argument("ClosedBSpline: points " + std::to_string(i) + " and " +
                                        std::to_string((i + 1) % n) + " coincide");
    }
    // At a knot the curve is (P[i-1] + 4 P[i] + P[i+1]) / 6: a cyclic, strictly diagonally
    // dominant system, so a dense LU is exact and, for the ~120 points of a hand, takes well
    // under a millisecond.
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd b(n, 2);
    for (int i = 0; i < n; ++i) {
        a(i, (i + n - 1) % n) += 1.0 / 6.0;
        a(i, i) += 4.0 / 6.0;
        a(i, (i + 1) % n) += 1.0 / 6.0;
        b(i, 0) = through[i].x;
        b(i, 1) = through[i].y;
    }
    const Eigen::MatrixXd p = a.partialPivLu().solve(b);
    ClosedBSpline s;
    s.control_.resize(n);
    for (int i = 0; i < n; ++i) s.control_[i] = {p(i, 0), p(i, 1)};
    double area2 = 0.0;  // twice the signed (shoelace) area of the interpolated ring
    for (int i = 0; i < n; ++i) {
        const auto& u = through[i];
        const auto& v = through[(i + 1) % n];
        area2 += u.x * v.y - v.x * u.y;
    }
    if (std::abs(area2) < 1e-9) throw std::invalid_argument("ClosedBSpline: the points enclose no area");
    s.orientation_ = area2 > 0 ? 1.0 : -1.0;
    return s;
}

// Sums the four control points of the span holding u (taken modulo the closed curve's
// length) with the weights `weights` gives for the position within the span.
cv::Point2d ClosedBSpline::blend(double u, void (*weights)(double, double*)) const
{
    const int n = size();
    double f = std::fmod(u, double(n));
    if (f < 0) f += n;
    int i = static_cast<int>(f);
    if (i >= n) i = n - 1;
    double w[4];
    weights(f - i, w);
    cv::Point2d p(0, 0);
    for (int k = 0; k < 4; ++k) p += w[k] * control_[(i - 1 + k + n) % n];
    return p;
}

cv::Point2d ClosedBSpline::point(double u) const { return blend(u, basis); }

cv::Point2d ClosedBSpline::derivative(double u) const { return blend(u, basis_derivative); }

cv::Point2d ClosedBSpline::outward_normal(double u) const
{
    const cv::Point2d d = derivative(u);
    const double len = std::hypot(d.x, d.y);
    if (len < 1e-12) return {0.0, 0.0};
    // For a ring with positive shoelace area in image axes (clockwise on screen) the
    // exterior lies on the side of (d.y, -d.x); the other orientation flips it.
    return {orientation_ * d.y / len, -orientation_ * d.x / len};
}

}  // namespace gc
