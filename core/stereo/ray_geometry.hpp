// Small 3D geometry of viewing rays: triangulation, planes, ray-plane intersection.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gc {

// n . x + d = 0 with |n| = 1.
struct Plane {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double d = 0.0;
    double distance(const Eigen::Vector3d& x) const { return std::abs(normal.dot(x) + d); }
};

// The plane a x + b y + c z + d = 0 with its normal made unit; nullopt when a coefficient is
// not finite or (a, b, c) is (nearly) zero.
std::optional<Plane> plane_from_coefficients(double a, double b, double c, double d);

// The midpoint of the shortest segment between the rays o1 + s d1 and o2 + t d2 (s, t > 0).
// Nullopt for (nearly) parallel rays or a point behind either origin.
std::optional<Eigen::Vector3d> triangulate_midpoint(const Eigen::Vector3d& o1, const Eigen::Vector3d& d1,
                                                    const Eigen::Vector3d& o2, const Eigen::Vector3d& d2);

// Where the ray o + s d (s > 0) meets the plane; nullopt when it runs (nearly) parallel to
// it or meets it behind the origin.
std::optional<Eigen::Vector3d> intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Plane& plane);

// The total-least-squares plane through the flagged points (at least 3, not collinear).
std::optional<Plane> fit_plane(std::span<const Eigen::Vector3d> points, std::span<const std::uint8_t> use);

// RANSAC over minimal triples, then least-squares refinement on the inliers. `inliers`
// receives one flag per point. Deterministic: the sampler restarts from `seed` each call.
class RobustPlaneFit {
public:
    RobustPlaneFit(int iterations, std::uint64_t seed) : iterations_(iterations), seed_(seed) {}

    // tolerance_mm: the largest point-to-plane distance of an inlier.
    std::optional<Plane> fit(std::span<const Eigen::Vector3d> points, double tolerance_mm,
                             std::vector<std::uint8_t>& inliers) const;

private:
    int iterations_;
    std::uint64_t seed_;
};

}  // namespace gc
