#include "sim/hand_gestures.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

// Proportions of the open hand's fingers against the index finger (root position in the
// default palm, length and radii relative to the index, spread): the middle finger is the
// longest, the little finger the shortest and thinnest.
struct OpenFinger {
    double base_u, base_v, length, base_radius, tip_radius, spread_deg;
};
constexpr OpenFinger kOpenFingers[] = {
    {35.0, 5.0, 1.10, 1.03, 1.02, 1.0},
    {33.0, -13.5, 1.02, 0.97, 0.96, -7.0},
    {28.0, -30.0, 0.80, 0.85, 0.84, -16.0},
};

cv::Point2d turned(cv::Point2d p, double deg)
{
    const double c = std::cos(deg * kPi / 180.0), s = std::sin(deg * kPi / 180.0);
    return {c * p.x - s * p.y, s * p.x + c * p.y};
}

FingerLayout pointing_layout(const HandShape& h)
{
    FingerLayout l;
    l.straight.push_back({h.index_base, h.index_base_radius, h.index_tip, h.index_tip_radius, 0.0});
    l.thumb = {h.thumb_base, h.thumb_base_radius, h.thumb_tip, h.thumb_tip_radius, 0.0};
    for (int i = 0; i < 3; ++i)
        l.curled.push_back({h.curled_centre[i], h.curled_length[i], h.curled_width[i], h.curled_angle_deg[i]});
    return l;
}

FingerLayout open_layout(const HandShape& h)
{
    const HandShape d;
    const double lx = h.palm_half_length / d.palm_half_length, ly = h.palm_half_width / d.palm_half_width;
    const double index_length = h.index_tip.x - h.index_base.x;
    FingerLayout l;
    l.straight.push_back({h.index_base, h.index_base_radius, h.index_tip, h.index_tip_radius, 8.0});
    for (const OpenFinger& f : kOpenFingers) {
        const cv::Point2d base(f.base_u * lx, f.base_v * ly);
        l.straight.push_back({base, h.index_base_radius * f.base_radius,
                              base + cv::Point2d(index_length * f.length, 0.0), h.index_tip_radius * f.tip_radius,
                              f.spread_deg});
    }
    // The thumb swung away from the index finger, a little longer where it no longer folds.
    const cv::Point2d along = turned(h.thumb_tip - h.thumb_base, 40.0) * 1.1;
    l.thumb = {h.thumb_base, h.thumb_base_radius, h.thumb_base + along, h.thumb_tip_radius, 0.0};
    return l;
}

FingerLayout fist_layout(const HandShape& h)
{
    const HandShape d;
    const double lx = h.palm_half_length / d.palm_half_length;
    FingerLayout l = pointing_layout(h);
    l.straight.clear();
    // The index finger curled beside the middle finger, a little larger (its knuckle leads).
    l.curled.insert(l.curled.begin(), CurledFinger{{h.curled_centre[0].x + 1.0 * lx, h.index_base.y},
                                                   h.curled_length[0] * 1.03,
                                                   h.index_base_radius * 1.1,
                                                   h.curled_angle_deg[0] - 6.0});
    // The thumb across the curled index and middle fingers.
    const double reach = std::hypot(h.thumb_tip.x - h.thumb_base.x, h.thumb_tip.y - h.thumb_base.y) /
                         std::hypot(d.thumb_tip.x - d.thumb_base.x, d.thumb_tip.y - d.thumb_base.y);
    l.thumb.tip = h.thumb_base + cv::Point2d(38.0 * lx, -26.0) * reach;
    l.thumb.tip_radius = h.thumb_tip_radius * 0.95;
    return l;
}

}  // namespace

FingerLayout finger_layout(const HandShape& shape, Gesture gesture)
{
    switch (gesture) {
    case Gesture::Pointing:
        return pointing_layout(shape);
    case Gesture::Open:
        return open_layout(shape);
    case Gesture::Fist:
        return fist_layout(shape);
    default:
        throw std::invalid_argument("finger_layout: the renderer shows pointing, open or fist");
    }
}

Gesture gesture_at(Gesture gesture, double cycle_s, double t)
{
    if (cycle_s <= 0.0) return gesture;
    return std::fmod(t, 2.0 * cycle_s) < cycle_s ? gesture : Gesture::Pointing;
}

}  // namespace gc::sim
