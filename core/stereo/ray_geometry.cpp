#include "stereo/ray_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>

namespace gc {

namespace {
// Rays closer to parallel than this (sine of the angle) give no usable depth.
constexpr double kMinSine = 1e-6;

// xorshift64*: a tiny, fast, reproducible generator for drawing sample indices.
struct SampleIndex {
    std::uint64_t state;
    std::size_t next(std::size_t n)
    {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        return static_cast<std::size_t>((state * 0x2545F4914F6CDD1DULL) >> 33) % n;
    }
};

std::size_t count_inliers(std::span<const Eigen::Vector3d> points, const Plane& plane, double tolerance,
                          std::vector<std::uint8_t>* flags)
{
    std::size_t n = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const bool in = plane.distance(points[i]) <= tolerance;
        n += in;
        if (flags) (*flags)[i] = in;
    }
    return n;
}
}  // namespace

std::optional<Eigen::Vector3d> triangulate_midpoint(const Eigen::Vector3d& o1, const Eigen::Vector3d& d1,
                                                    const Eigen::Vector3d& o2, const Eigen::Vector3d& d2)
{
    // Minimise |o1 + s d1 - o2 - t d2|^2: a 2x2 linear system in (s, t).
    const Eigen::Vector3d w = o1 - o2;
    const double a = d1.dot(d1), b = d1.dot(d2), c = d2.dot(d2);
    const double e = d1.dot(w), f = d2.dot(w);
    const double det = a * c - b * b;
    if (det <= kMinSine * kMinSine * a * c) return std::nullopt;
    const double s = (b * f - c * e) / det;
    const double t = (a * f - b * e) / det;
    if (s <= 0.0 || t <= 0.0) return std::nullopt;
    return 0.5 * ((o1 + s * d1) + (o2 + t * d2));
}

std::optional<Plane> plane_from_coefficients(double a, double b, double c, double d)
{
    if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d))) return std::nullopt;
    const Eigen::Vector3d n(a, b, c);
    const double length = n.norm();
    if (!(length > 1e-9)) return std::nullopt;
    return Plane{n / length, d / length};
}

std::optional<Eigen::Vector3d> intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Plane& plane)
{
    const double denom = plane.normal.dot(d);
    if (std::abs(denom) <= kMinSine * d.norm()) return std::nullopt;
    const double s = -(plane.normal.dot(o) + plane.d) / denom;
    if (s <= 0.0) return std::nullopt;
    return o + s * d;
}

std::optional<Plane> fit_plane(std::span<const Eigen::Vector3d> points, std::span<const std::uint8_t> use)
{
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::size_t n = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (use[i]) centroid += points[i], ++n;
    if (n < 3) return std::nullopt;
    centroid /= static_cast<double>(n);
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i)
        if (use[i]) {
            const Eigen::Vector3d q = points[i] - centroid;
            scatter.noalias() += q * q.transpose();
        }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    if (solver.info() != Eigen::Success) return std::nullopt;
    const Eigen::Vector3d eig = solver.eigenvalues();  // ascending
    // Collinear points: the two smallest spreads both vanish and the normal is undefined.
    if (!(eig[1] > 1e-9 * eig[2])) return std::nullopt;
    Plane plane;
    plane.normal = solver.eigenvectors().col(0).normalized();
    plane.d = -plane.normal.dot(centroid);
    return plane;
}

std::optional<Plane> RobustPlaneFit::fit(std::span<const Eigen::Vector3d> points, double tolerance_mm,
                                         std::vector<std::uint8_t>& inliers) const
{
    const std::size_t n = points.size();
    inliers.assign(n, 0);
    if (n < 3) return std::nullopt;

    SampleIndex rng{seed_ | 1};
    Plane best;
    std::size_t best_count = 0;
    for (int it = 0; it < iterations_; ++it) {
        const std::size_t i = rng.next(n), j = rng.next(n), k = rng.next(n);
        if (i == j || j == k || i == k) continue;
        const Eigen::Vector3d normal = (points[j] - points[i]).cross(points[k] - points[i]);
        const double len = normal.norm();
        if (!(len > 1e-9)) continue;
        Plane candidate;
        candidate.normal = normal / len;
        candidate.d = -candidate.normal.dot(points[i]);
        const std::size_t count = count_inliers(points, candidate, tolerance_mm, nullptr);
        if (count > best_count) best_count = count, best = candidate;
    }
    if (best_count < 3) return std::nullopt;

    // Refit on the consensus, then once more on the refit's inliers.
    std::optional<Plane> plane = best;
    for (int round = 0; round < 2; ++round) {
        count_inliers(points, *plane, tolerance_mm, &inliers);
        const std::optional<Plane> refined = fit_plane(points, inliers);
        if (!refined) break;
        plane = refined;
    }
    count_inliers(points, *plane, tolerance_mm, &inliers);
    return plane;
}

}  // namespace gc
