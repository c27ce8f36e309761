// A closed, uniform cubic B-spline that interpolates a ring of points: the hand outline.
// The parameter u runs over [0, n) with u = i at the i-th interpolated point, so where the
// points are dense (the index finger) the curve is sampled densely at uniform u as well.
#pragma once

#include <opencv2/core.hpp>

#include <span>
#include <vector>

namespace gc {

class ClosedBSpline {
public:
    // Control points are solved so that the curve passes through every point of `through`
    // (a cyclic tridiagonal system). Throws std::invalid_argument on fewer than 4 points,
    // non-finite coordinates, or two consecutive points that coincide.
    static ClosedBSpline interpolate(std::span<const cv::Point2d> through);

    int size() const { return static_cast<int>(control_.size()); }

    // u is taken modulo size().
    cv::Point2d point(double u) const;
    cv::Point2d derivative(double u) const;
    // Unit normal pointing from the interior to the exterior of the closed curve.
    cv::Point2d outward_normal(double u) const;

private:
    cv::Point2d blend(double u, void (*weights)(double, double*)) const;
    std::vector<cv::Point2d> control_;
    double orientation_ = 1.0;  // +1 or -1: the sign that turns a tangent's normal outward
};

}  // namespace gc
