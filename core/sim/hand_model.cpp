#include "sim/hand_model.hpp"

#include "sim/hand_gestures.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kTexelMm = 0.4;
constexpr double kPi = std::numbers::pi;

using Poly = std::vector<cv::Point2d>;

// Rounded rectangle: |u/a|^e + |v/b|^e = 1.
Poly superellipse(double a, double b, double e, int n)
{
    auto root = [e](double x) { return e == 4.0 ? std::sqrt(std::abs(x)) : std::pow(std::abs(x), 2.0 / e); };
    Poly p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * kPi * i / n;
        const double c = std::cos(t), s = std::sin(t);
        p.emplace_back(a * std::copysign(root(c), c), b * std::copysign(root(s), s));
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
    cv::polylines(layer, std::vector<std::vector<cv::Point>>{pts}, false, cv::Scalar(1.0), thickness, cv::LINE_AA, 4);
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

// The hand's outline in the anatomical layout (the palm's long axis along u), turned so that
// the pointing fingertip lies on +u, mirrored for the other hand; `j` is the seeded size
// factor. Every gesture is turned like the pointing hand, so palm and wrist stay in place.
struct Outline {
    HandModel model;  // parts, finger length, palm axis, wrist
    FingerLayout layout;
    std::size_t thumb_part = 0, first_curled = 0;
    double turn_cos = 1.0, turn_sin = 0.0, v_sign = 1.0;

    Poly place(Poly p) const
    {
        for (auto& q : p) {
            q = rotate(q, turn_cos, turn_sin);
            q.y *= v_sign;
        }
        return p;
    }
};

// A straight finger's polygon (or a line along it) turned about the finger's root.
Poly spread(Poly p, const StraightFinger& f, double j)
{
    if (f.spread_deg == 0.0) return p;
    const double a = f.spread_deg * kPi / 180.0;
    const cv::Point2d root = f.base * j;
    for (auto& q : p) q = root + rotate(q - root, std::cos(a), std::sin(a));
    return p;
}

// The farthest the hand reaches along +u: where a hand that does not point has its "tip".
double reach_along_u(const std::vector<Poly>& parts)
{
    double reach = 0.0;
    for (const auto& part : parts)
        for (const auto& q : part) reach = std::max(reach, q.x);
    return reach;
}

Outline hand_outline(const HandShape& h, Gesture gesture, double j, bool mirrored)
{
    const cv::Point2d tip_centre = h.index_tip * j;
    const double tip_r = h.index_tip_radius * j;
    const Poly palm = superellipse(h.palm_half_length * j, h.palm_half_width * j, h.palm_exponent, 64);
    const double edge = h.palm_half_length - 7.0, joint = h.wrist_half_width + 4.0;
    const Poly wrist{{-edge * j, joint * j},
                     {-h.wrist_length * j, h.wrist_half_width * j},
                     {-h.wrist_length * j, -h.wrist_half_width * j},
                     {-edge * j, -joint * j}};

    // The fingertip: the point of the finger's end cap farthest from the palm centroid, so
    // that it is also the hand's extreme point along the pointing direction.
    cv::Point2d tip(tip_centre.x + tip_r, tip_centre.y);
    for (int i = 0; i < 8; ++i) tip = tip_centre + tip * (tip_r / std::hypot(tip.x, tip.y));
    const double turn = -std::atan2(tip.y, tip.x);
    Outline o;
    o.layout = finger_layout(h, gesture);
    o.turn_cos = std::cos(turn);
    o.turn_sin = std::sin(turn);
    o.v_sign = mirrored ? -1.0 : 1.0;

    HandModel& m = o.model;
    m.gesture = gesture;
    m.finger_length_mm = std::hypot(tip.x, tip.y);
    m.palm_axis = rotate({-1.0, 0.0}, o.turn_cos, o.turn_sin);
    m.palm_axis.y *= o.v_sign;
    m.wrist_mm = h.wrist_length * j;
    m.parts = {o.place(palm), o.place(wrist)};
    for (const StraightFinger& f : o.layout.straight)
        m.parts.push_back(o.place(spread(capsule(f.base * j, f.base_radius * j, f.tip * j, f.tip_radius * j, 24), f, j)));
    const StraightFinger& t = o.layout.thumb;
    o.thumb_part = m.parts.size();
    m.parts.push_back(o.place(capsule(t.base * j, t.base_radius * j, t.tip * j, t.tip_radius * j, 24)));
    o.first_curled = m.parts.size();
    for (const CurledFinger& c : o.layout.curled)
        m.parts.push_back(o.place(ellipse(c.centre * j, c.length * j, c.width * j, c.angle_deg, 32)));
    if (gesture != Gesture::Pointing) m.finger_length_mm = reach_along_u(m.parts);
    return o;
}

// Brightness over the hand's texels: a smooth gradient across it, parts slightly apart in
// tone, creases, darkening towards the silhouette (the surface turns away from the light).
cv::Mat1f skin_shading(const Outline& o, const HandShape& h, double j, double gradient, const cv::Mat1f& dist, Rng& rng)
{
    const HandModel& m = o.model;
    const cv::Size size = dist.size();
    cv::Mat1f shade(size, 1.0f);
    const double g_angle = uniform(rng, 0.0, 2.0 * kPi);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const double u = m.texture_origin.x + x * kTexelMm;
            const double v = m.texture_origin.y - y * kTexelMm;
            shade(y, x) = float(1.0 + gradient * (u * std::cos(g_angle) + v * std::sin(g_angle)) / 80.0);
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
    part_gain(m.parts[o.thumb_part], 0.97f);  // thumb
    for (std::size_t i = o.first_curled; i < m.parts.size(); ++i) part_gain(m.parts[i], 0.93f);

    // Creases: where the curled fingers fold (and a fist's thumb lies across them), the palm
    // lines, the straight fingers' joints.
    const std::size_t first_outlined = m.gesture == Gesture::Fist ? o.thumb_part : o.first_curled;
    for (std::size_t i = first_outlined; i < m.parts.size(); ++i) {
        Poly outline = m.parts[i];
        outline.push_back(outline.front());
        crease(shade, m, outline, 1.1, 0.22f);
    }
    const double sx = j * (h.palm_half_length / 45.0), sy = j * (h.palm_half_width / 40.0);
    crease(shade, m, o.place(arc({-6 * sx, -2 * sy}, 32 * sx, 24 * sy, -15, 200, 300)), 0.9, 0.12f);
    crease(shade, m, o.place(arc({10 * sx, 28 * sy}, 40 * sx, 20 * sy, 10, 200, 280)), 0.9, 0.12f);
    crease(shade, m, o.place(arc({-20 * sx, 22 * sy}, 28 * sx, 40 * sy, 0, 260, 350)), 0.9, 0.14f);
    for (const StraightFinger& f : o.layout.straight)
        for (double k : {0.42, 0.72}) {
            const double u = f.base.x * j + k * (f.tip.x - f.base.x) * j;
            const Poly joint{{u, (f.base.y - 8.5) * j}, {u + 1.0, (f.base.y + 8.5) * j}};
            crease(shade, m, o.place(spread(joint, f, j)), 0.8, 0.18f);
        }

    const float rim_texels = float(5.0 / kTexelMm);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) shade(y, x) *= 0.80f + 0.20f * std::min(1.0f, dist(y, x) / rim_texels);
    return shade;
}

}  // namespace

cv::Matx33d HandModel::texel_to_model() const
{
    return {texel_mm, 0.0, texture_origin.x, 0.0, -texel_mm, texture_origin.y, 0.0, 0.0, 1.0};
}

HandModel build_hand_model(const cv::Vec3f& skin_bgr, bool mirrored, Rng& rng, const HandShape& shape,
                           const HandSkin* skin, Gesture gesture)
{
    const double jitter = uniform(rng, 0.95, 1.05);  // hand size
    Outline o = hand_outline(shape, gesture, jitter, mirrored);
    HandModel& m = o.model;

    // Texture over the parts' bounding box plus a margin.
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    for (const auto& part : m.parts)
        for (const auto& q : part) {
            u0 = std::min(u0, q.x);
            u1 = std::max(u1, q.x);
            v0 = std::min(v0, q.y);
            v1 = std::max(v1, q.y);
        }
    constexpr double kMargin = 4.0;
    m.texel_mm = kTexelMm;
    m.texture_origin = {u0 - kMargin, v1 + kMargin};
    const cv::Size size(int(std::ceil((u1 - u0 + 2 * kMargin) / kTexelMm)),
                        int(std::ceil((v1 - v0 + 2 * kMargin) / kTexelMm)));

    cv::Mat1b inside(size, std::uint8_t{0});
    for (const auto& part : m.parts) cv::fillConvexPoly(inside, to_texels(part, m), cv::Scalar(255), cv::LINE_8, 4);
    cv::Mat1f dist;
    cv::distanceTransform(inside, dist, cv::DIST_L2, 3);

    cv::RNG cvrng(std::uniform_int_distribution<std::uint64_t>()(rng));
    const cv::Mat1f shade = skin_shading(o, shape, jitter, skin ? skin->gradient : 0.07, dist, rng);

    // Skin texture: blotches of brightness and of redness, and fine grain; with a HandSkin,
    // the palm's tone turns into the back's towards the silhouette.
    const cv::Mat1f blotch = smooth_noise(size, 6.0 / kTexelMm, cvrng);
    const cv::Mat1f redness = smooth_noise(size, 10.0 / kTexelMm, cvrng);
    cv::Mat1f grain(size);
    cvrng.fill(grain, cv::RNG::NORMAL, 0.0, 1.0);
    const float blotches = skin ? float(skin->blotches) : 0.03f;
    const float rim = skin ? float(skin->rim_mm / kTexelMm) : 1.0f;

    m.texture.create(size);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const float k = shade(y, x) * (1.0f + blotches * blotch(y, x) + 0.012f * grain(y, x));
            const float red = 1.0f + 0.025f * redness(y, x);
            cv::Vec3f tone = skin_bgr;
            if (skin) {
                const float w = std::min(1.0f, dist(y, x) / rim);
                tone = skin->back + w * (skin->palm - skin->back);
            }
            m.texture(y, x) = {cv::saturate_cast<std::uint8_t>(tone[0] * k),
                               cv::saturate_cast<std::uint8_t>(tone[1] * k),
                               cv::saturate_cast<std::uint8_t>(tone[2] * k * red)};
        }
    return m;
}

}  // namespace gc::sim
