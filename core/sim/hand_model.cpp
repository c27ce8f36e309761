#include "sim/hand_model.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kTexelMm = 0.4;
constexpr double kPi = std::numbers::pi;

using Poly = std::vector<cv::Point2d>;

// Rounded rectangle: |u/a|^4 + |v/b|^4 = 1.
Poly superellipse(double a, double b, int n)
{
    Poly p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * kPi * i / n;
        const double c = std::cos(t), s = std::sin(t);
        p.emplace_back(a * std::copysign(std::sqrt(std::abs(c)), c),
                       b * std::copysign(std::sqrt(std::abs(s)), s));
    }
    return p;
}

Poly ellipse(cv::Point2d c, double a, double b, double angle_deg, int n)
{
    const double ca = std::cos(angle_deg * kPi / 180.0), sa = std::sin(angle_deg * kPi / 180.0);
    Poly p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * kPi * i / n;
        const double x = a * std::cos(t), y = b * std::sin(t);
        p.emplace_back(c.x + ca * x - sa * y, c.y + sa * x + ca * y);
    }
    return p;
}

// Convex hull of two discs: a tapered finger.
Poly capsule(cv::Point2d a, double ra, cv::Point2d b, double rb, int n)
{
    std::vector<cv::Point2f> pts;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * kPi * i / n;
        pts.emplace_back(float(a.x + ra * std::cos(t)), float(a.y + ra * std::sin(t)));
        pts.emplace_back(float(b.x + rb * std::cos(t)), float(b.y + rb * std::sin(t)));
    }
    std::vector<cv::Point2f> hull;
    cv::convexHull(pts, hull);
    Poly p;
    for (const auto& q : hull) p.emplace_back(q.x, q.y);
    return p;
}

cv::Point2d rotate(cv::Point2d p, double c, double s) { return {c * p.x - s * p.y, s * p.x + c * p.y}; }

std::vector<cv::Point> to_texels(const Poly& poly, const HandModel& m)
{
    std::vector<cv::Point> out;
    for (const auto& p : poly)
        out.emplace_back(cvRound((p.x - m.texture_origin.x) / m.texel_mm * 16.0),
                         cvRound((m.texture_origin.y - p.y) / m.texel_mm * 16.0));
    return out;
}

void crease(cv::Mat1f& shade, const HandModel& m, const Poly& line, double width_mm, float depth)
{
    const std::vector<cv::Point> pts = to_texels(line, m);
    const int thickness = std::max(1, int(std::lround(width_mm / m.texel_mm)));
    cv::Mat1f layer(shade.size(), 0.f);
    cv::polylines(layer, std::vector<std::vector<cv::Point>>{pts}, false, cv::Scalar(1.0),
                  thickness, cv::LINE_AA, 4);
    cv::GaussianBlur(layer, layer, cv::Size(0, 0), 0.6 / m.texel_mm);
    shade -= depth * layer;
}

Poly arc(cv::Point2d c, double a, double b, double angle_deg, double from_deg, double to_deg)
{
    Poly p;
    const double ca = std::cos(angle_deg * kPi / 180.0), sa = std::sin(angle_deg * kPi / 180.0);
    for (int i = 0; i <= 16; ++i) {
        const double t = (from_deg + (to_deg - from_deg) * i / 16.0) * kPi / 180.0;
        const double x = a * std::cos(t), y = b * std::sin(t);
        p.emplace_back(c.x + ca * x - sa * y, c.y + sa * x + ca * y);
    }
    return p;
}

}  // namespace

cv::Matx33d HandModel::texel_to_model() const
{
    return {texel_mm, 0.0, texture_origin.x, 0.0, -texel_mm, texture_origin.y, 0.0, 0.0, 1.0};
}

HandModel build_hand_model(const cv::Vec3f& skin, bool mirrored, Rng& rng)
{
    // Anatomical layout with the palm's long axis along u; the index lies along the thumb's
    // edge of the palm, so the palm-to-fingertip line is turned against that axis.
    const double jitter = uniform(rng, 0.95, 1.05);  // hand size
    const cv::Point2d tip_centre(108.0 * jitter, 24.0 * jitter);
    const double tip_r = 8.2 * jitter;
    Poly palm = superellipse(45.0 * jitter, 40.0 * jitter, 64);
    Poly wrist{{-38.0 * jitter, 31.0 * jitter}, {-80.0 * jitter, 27.0 * jitter},
               {-80.0 * jitter, -27.0 * jitter}, {-38.0 * jitter, -31.0 * jitter}};
    Poly index = capsule({32.0 * jitter, 24.0 * jitter}, 9.5 * jitter, tip_centre, tip_r, 24);
    Poly thumb = capsule({-2.0 * jitter, 36.0 * jitter}, 12.5 * jitter,
                         {30.0 * jitter, 44.0 * jitter}, 10.0 * jitter, 24);
    const cv::Point2d curl_c[3] = {{46.0, 5.0}, {43.0, -15.0}, {38.0, -32.0}};
    const double curl_a[3] = {15.5, 14.5, 12.0}, curl_b[3] = {10.5, 10.0, 8.5};
    const double curl_angle[3] = {-8.0, 0.0, 10.0};
    std::vector<Poly> curled;
    for (int i = 0; i < 3; ++i)
        curled.push_back(ellipse(curl_c[i] * jitter, curl_a[i] * jitter, curl_b[i] * jitter,
                                 curl_angle[i], 32));

    // The fingertip: the point of the finger's end cap farthest from the palm centroid, so
    // that it is also the hand's extreme point along the pointing direction.
    cv::Point2d tip(tip_centre.x + tip_r, tip_centre.y);
    for (int i = 0; i < 8; ++i) tip = tip_centre + tip * (tip_r / std::hypot(tip.x, tip.y));
    const double turn = -std::atan2(tip.y, tip.x);
    const double c = std::cos(turn), s = std::sin(turn);
    const double vs = mirrored ? -1.0 : 1.0;
    auto place = [&](Poly p) {
        for (auto& q : p) {
            q = rotate(q, c, s);
            q.y *= vs;
        }
        return p;
    };

    HandModel m;
    m.finger_length_mm = std::hypot(tip.x, tip.y);
    m.palm_axis = rotate({-1.0, 0.0}, c, s);
    m.palm_axis.y *= vs;
    m.wrist_mm = 80.0 * jitter;
    m.parts = {place(palm), place(wrist), place(index), place(thumb)};
    const std::size_t first_curled = m.parts.size();
    for (const auto& p : curled) m.parts.push_back(place(p));

    // Texture over the parts' bounding box plus a margin.
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    for (const auto& part : m.parts)
        for (const auto& q : part) {
            u0 = std::min(u0, q.x); u1 = std::max(u1, q.x);
            v0 = std::min(v0, q.y); v1 = std::max(v1, q.y);
        }
    constexpr double kMargin = 4.0;
    m.texel_mm = kTexelMm;
    m.texture_origin = {u0 - kMargin, v1 + kMargin};
    const cv::Size size(int(std::ceil((u1 - u0 + 2 * kMargin) / kTexelMm)),
                        int(std::ceil((v1 - v0 + 2 * kMargin) / kTexelMm)));

    cv::Mat1b inside(size, std::uint8_t{0});
    for (const auto& part : m.parts)
        cv::fillConvexPoly(inside, to_texels(part, m), cv::Scalar(255), cv::LINE_8, 4);

    // Brightness: a smooth gradient across the hand, parts slightly apart in tone, creases,
    // darkening towards the silhouette (the surface turns away from the light there).
    cv::RNG cvrng(std::uniform_int_distribution<std::uint64_t>()(rng));
    cv::Mat1f shade(size, 1.0f);
    const double g_angle = uniform(rng, 0.0, 2.0 * kPi);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const double u = m.texture_origin.x + x * kTexelMm;
            const double v = m.texture_origin.y - y * kTexelMm;
            shade(y, x) = float(1.0 + 0.07 * (u * std::cos(g_angle) + v * std::sin(g_angle)) / 80.0);
        }
    auto part_gain = [&](const Poly& part, float gain) {
        cv::Mat1b pm(size, std::uint8_t{0});
        cv::fillConvexPoly(pm, to_texels(part, m), cv::Scalar(255), cv::LINE_8, 4);
        cv::Mat1f g(size, 1.0f);
        g.setTo(gain, pm);
        cv::GaussianBlur(g, g, cv::Size(0, 0), 1.0 / kTexelMm);
        shade = shade.mul(g);
    };
    part_gain(m.parts[1], 0.96f);  // wrist
    part_gain(m.parts[3], 0.97f);  // thumb
    for (std::size_t i = first_curled; i < m.parts.size(); ++i) part_gain(m.parts[i], 0.93f);

    // Creases: where the curled fingers fold, the palm lines, the index finger's joints.
    for (std::size_t i = first_curled; i < m.parts.size(); ++i) {
        Poly outline = m.parts[i];
        outline.push_back(outline.front());
        crease(shade, m, outline, 1.1, 0.22f);
    }
    const double sj = jitter;
    crease(shade, m, place(arc({-6 * sj, -2 * sj}, 32 * sj, 24 * sj, -15, 200, 300)), 0.9, 0.12f);
    crease(shade, m, place(arc({10 * sj, 28 * sj}, 40 * sj, 20 * sj, 10, 200, 280)), 0.9, 0.12f);
    crease(shade, m, place(arc({-20 * sj, 22 * sj}, 28 * sj, 40 * sj, 0, 260, 350)), 0.9, 0.14f);
    for (double k : {0.42, 0.72}) {
        const double u = 32 * sj + k * (108 - 32) * sj;
        crease(shade, m, place(Poly{{u, 15.5 * sj}, {u + 1.0, 32.5 * sj}}), 0.8, 0.18f);
    }

    cv::Mat1f dist;
    cv::distanceTransform(inside, dist, cv::DIST_L2, 3);
    const float rim_texels = float(5.0 / kTexelMm);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
            shade(y, x) *= 0.80f + 0.20f * std::min(1.0f, dist(y, x) / rim_texels);

    // Skin texture: blotches of brightness and of redness, and fine grain.
    const cv::Mat1f blotch = smooth_noise(size, 6.0 / kTexelMm, cvrng);
    const cv::Mat1f redness = smooth_noise(size, 10.0 / kTexelMm, cvrng);
    cv::Mat1f grain(size);
    cvrng.fill(grain, cv::RNG::NORMAL, 0.0, 1.0);

    m.texture.create(size);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const float k = shade(y, x) * (1.0f + 0.03f * blotch(y, x) + 0.012f * grain(y, x));
            const float red = 1.0f + 0.025f * redness(y, x);
            m.texture(y, x) = {cv::saturate_cast<std::uint8_t>(skin[0] * k),
                               cv::saturate_cast<std::uint8_t>(skin[1] * k),
                               cv::saturate_cast<std::uint8_t>(skin[2] * k * red)};
        }
    return m;
}

}  // namespace gc::sim
