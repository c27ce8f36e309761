#include "sim/figures.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kScale = double(1 << kDrawShift);

std::vector<cv::Point2d> ellipse_points(cv::Point2d c, double a, double b, int n = 40)
{
    std::vector<cv::Point2d> p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * kPi * i / n;
        p.emplace_back(c.x + a * std::cos(t), c.y + b * std::sin(t));
    }
    return p;
}

std::vector<cv::Point2d> rect_points(double x0, double y0, double x1, double y1)
{
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

cv::Point fixed(cv::Point2d p) { return {cvRound(p.x * kScale), cvRound(p.y * kScale)}; }

}  // namespace

bool project_polygon(const EyeCamera& cam, const cv::Vec3d& origin, const cv::Vec3d& e1, const cv::Vec3d& e2,
                     const std::vector<cv::Point2d>& poly, std::vector<cv::Point>& out, cv::Point offset,
                     double min_depth_mm)
{
    out.clear();
    for (const auto& q : poly) {
        const cv::Vec3d c = cam.to_camera(origin + q.x * e1 + q.y * e2);
        if (c[2] < min_depth_mm) return false;
        const cv::Point2d px = cam.project_camera(c);
        out.push_back(fixed(px - cv::Point2d(offset)));
    }
    return true;
}

void draw_tube(cv::Mat& bgr, const EyeCamera& cam, const Tube& tube, const cv::Vec3f& colour,
               const std::vector<double>& folds)
{
    const cv::Vec3d ca = cam.to_camera(tube.a), cb = cam.to_camera(tube.b);
    if (ca[2] < 50.0 || cb[2] < 50.0) return;
    const cv::Point2d a = cam.project_camera(ca), b = cam.project_camera(cb);
    const double f = cam.K(0, 0);
    const double ra = f * tube.ra / ca[2], rb = f * tube.rb / cb[2];
    const cv::Point2d d = b - a;
    const double len = std::hypot(d.x, d.y);
    std::vector<cv::Point2f> outline;
    for (int i = 0; i < 24; ++i) {
        const double t = 2.0 * kPi * i / 24;
        outline.emplace_back(float(a.x + ra * std::cos(t)), float(a.y + ra * std::sin(t)));
        outline.emplace_back(float(b.x + rb * std::cos(t)), float(b.y + rb * std::sin(t)));
    }
    std::vector<cv::Point2f> hull;
    cv::convexHull(outline, hull);
    std::vector<cv::Point> pts;
    for (const auto& p : hull) pts.push_back(fixed(p));
    cv::fillConvexPoly(bgr, pts, to_scalar(colour, 0.55), cv::LINE_AA, kDrawShift);
    if (len < 1.0) return;

    // Cylinder shading in strips across the tube, lit from the upper left.
    const cv::Point2d n(-d.y / len, d.x / len);
    const double light_side = n.x * -0.6 + n.y * -0.8 > 0 ? 1.0 : -1.0;
    constexpr int kStrips = 7;
    for (int k = 0; k < kStrips; ++k) {
        const double s0 = -1.0 + 2.0 * k / kStrips, s1 = -1.0 + 2.0 * (k + 1) / kStrips;
        const double sm = 0.5 * (s0 + s1);
        const double gain = 0.55 + 0.4 * std::sqrt(1.0 - sm * sm) + 0.12 * light_side * sm;
        const std::vector<cv::Point> strip{fixed(a + n * (ra * s0)), fixed(a + n * (ra * s1)), fixed(b + n * (rb * s1)),
                                           fixed(b + n * (rb * s0))};
        cv::fillConvexPoly(bgr, strip, to_scalar(colour, gain), cv::LINE_AA, kDrawShift);
    }
    for (double t : folds) {
        const cv::Point2d c = a + d * t;
        const double r = ra + (rb - ra) * t;
        cv::line(bgr, fixed(c - n * (0.9 * r)), fixed(c + n * (0.9 * r) + d * (0.03)), to_scalar(colour, 0.6),
                 std::max(1, int(r / 12)), cv::LINE_AA, kDrawShift);
    }
}

Billboard build_person(const cv::Vec3d& face_centre_mm, const cv::Vec3f& skin, Rng& rng, double scale, bool shaded)
{
    Billboard b;
    b.centre_mm = face_centre_mm;
    const cv::Scalar hair = to_scalar(non_skin_colour(rng, 0.04, 0.1, 0.3));
    const cv::Scalar shirt = to_scalar(non_skin_colour(rng, 0.2, 0.8, 0.6));
    const double face_gain = uniform(rng, 0.9, 1.0);
    const cv::Scalar face = to_scalar(skin, face_gain);
    const cv::Scalar shade = to_scalar(skin, 0.8 * face_gain);
    const cv::Scalar white = to_scalar(non_skin_colour(rng, 0.85, 0.95, 0.05));
    const cv::Scalar iris = to_scalar(non_skin_colour(rng, 0.1, 0.35, 0.5));
    const cv::Scalar lips(skin[0] * 0.75, skin[1] * 0.6, std::min(255.0f, skin[2] * 0.95f));

    auto add = [&](std::vector<cv::Point2d> p, cv::Scalar c, bool skin_layer = false) {
        b.layers.push_back({std::move(p), c, skin_layer});
    };
    add(ellipse_points({0, 330}, 230, 190), shirt);       // shoulders
    add(rect_points(-52, 60, 52, 200), shade, true);      // neck
    add(ellipse_points({0, -30}, 86, 112), hair);         // back of the hair
    add(ellipse_points({-72, 12}, 13, 24), shade, true);  // ears
    add(ellipse_points({72, 12}, 13, 24), shade, true);
    add(ellipse_points({0, 10}, 72, 100), shaded ? shade : face, true);
    if (shaded) {  // the lit side of the face
        const double side = uniform(rng, -1.0, 1.0);
        add(ellipse_points({side * 16, 8}, 58, 94), face, true);
    }
    add(ellipse_points({0, -78}, 70, 30), hair);  // fringe
    for (double s : {-1.0, 1.0}) {
        add(ellipse_points({s * 28, -4}, 12, 5.5), white);
        add(ellipse_points({s * 28, -4}, 4.5, 4.5), iris);
        add(rect_points(s * 28 - 15, -22, s * 28 + 15, -17), hair);  // brows
    }
    add({{-3, 0}, {3, 0}, {9, 34}, {-9, 34}}, shade, true);  // nose
    add(ellipse_points({0, 55}, 22, 7), lips);
    if (scale != 1.0)
        for (auto& layer : b.layers)
            for (auto& p : layer.polygon) p *= scale;
    return b;
}

void draw_billboard(cv::Mat& bgr, const EyeCamera& cam, const Billboard& person, cv::Mat1b* skin_mask)
{
    std::vector<cv::Point> pts;
    for (const auto& layer : person.layers)
        if (project_polygon(cam, person.centre_mm, {1, 0, 0}, {0, 1, 0}, layer.polygon, pts)) {
            cv::fillConvexPoly(bgr, pts, layer.colour, cv::LINE_AA, kDrawShift);
            if (skin_mask)
                cv::fillConvexPoly(*skin_mask, pts, cv::Scalar(layer.skin ? 255 : 0), cv::LINE_8, kDrawShift);
        }
}

}  // namespace gc::sim
