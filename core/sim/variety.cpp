#include "sim/variety.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;

double log_uniform(Rng& rng, double lo, double hi) { return std::exp(uniform(rng, std::log(lo), std::log(hi))); }

// Palm-side tones of lit skin (BGR) from very fair to very dark, evenly spaced in darkness.
constexpr std::array<std::array<float, 3>, 6> kPalmTones{{
    {178.f, 196.f, 238.f},
    {140.f, 165.f, 222.f},
    {106.f, 138.f, 200.f},
    {78.f, 106.f, 166.f},
    {55.f, 77.f, 126.f},
    {38.f, 53.f, 90.f},
}};

cv::Vec3f palm_tone(double darkness)
{
    const double x = std::clamp(darkness, 0.0, 1.0) * (kPalmTones.size() - 1);
    const std::size_t i = std::min<std::size_t>(std::size_t(x), kPalmTones.size() - 2);
    const double w = x - double(i);
    cv::Vec3f c;
    for (int k = 0; k < 3; ++k) c[k] = float((1.0 - w) * kPalmTones[i][k] + w * kPalmTones[i + 1][k]);
    return c;
}

}  // namespace

HandShape pick_hand_shape(Rng& rng)
{
    HandShape h;
    const HandShape d;
    const double lx = uniform(rng, 0.9, 1.1), ly = uniform(rng, 0.88, 1.12);
    h.palm_half_length = d.palm_half_length * lx;
    h.palm_half_width = d.palm_half_width * ly;
    h.palm_exponent = uniform(rng, 2.6, 5.5);

    const double length = uniform(rng, 0.88, 1.12), width = uniform(rng, 0.82, 1.18);
    h.index_base = {d.index_base.x * lx, d.index_base.y * ly};
    h.index_tip = {h.index_base.x + (d.index_tip.x - d.index_base.x) * length, h.index_base.y};
    h.index_base_radius = d.index_base_radius * width;
    h.index_tip_radius = d.index_tip_radius * width * uniform(rng, 0.92, 1.05);

    // The thumb swings about its root from tucked along the index to spread away from it.
    const double swing = uniform(rng, -15.0, 40.0) * kPi / 180.0, reach = uniform(rng, 0.9, 1.1);
    const double thick = uniform(rng, 0.85, 1.15);
    h.thumb_base = {d.thumb_base.x * lx, d.thumb_base.y * ly};
    const cv::Point2d along = (d.thumb_tip - d.thumb_base) * reach;
    h.thumb_tip = h.thumb_base + cv::Point2d(along.x * std::cos(swing) - along.y * std::sin(swing),
                                             along.x * std::sin(swing) + along.y * std::cos(swing));
    h.thumb_base_radius = d.thumb_base_radius * thick;
    h.thumb_tip_radius = d.thumb_tip_radius * thick;

    // The curled fingers, each a little more or less tightly curled and turned.
    for (int i = 0; i < 3; ++i) {
        h.curled_centre[i] = {d.curled_centre[i].x * lx + uniform(rng, -3.0, 4.0),
                              d.curled_centre[i].y * ly + uniform(rng, -2.0, 2.0)};
        h.curled_length[i] = d.curled_length[i] * uniform(rng, 0.85, 1.2);
        h.curled_width[i] = d.curled_width[i] * uniform(rng, 0.9, 1.1);
        h.curled_angle_deg[i] = d.curled_angle_deg[i] + uniform(rng, -10.0, 10.0);
    }
    h.wrist_length = uniform(rng, 65.0, 110.0);
    h.wrist_half_width = d.wrist_half_width * uniform(rng, 0.85, 1.1);
    return h;
}

namespace {

CameraLooks pick_camera(double noise_sigma, Rng& rng)
{
    CameraLooks c;
    c.noise_sigma = noise_sigma * log_uniform(rng, 0.5, 4.0);
    c.defocus_sigma_px = uniform(rng, 0, 1) < 0.5 ? uniform(rng, 0.4, 1.2) : 0.0;
    c.shutter_s = log_uniform(rng, 1.0 / 250.0, 1.0 / 25.0);
    c.jpeg_quality = uniform(rng, 0, 1) < 0.35 ? int(std::lround(uniform(rng, 30.0, 85.0))) : 0;
    c.exposure = uniform(rng, 0.75, 1.25);
    const double drift = uniform(rng, 0.0, 0.2);
    for (int k = 0; k < 2; ++k) {
        c.drift_amplitude[k] = 0.5 * drift;
        c.drift_omega[k] = 2.0 * kPi * uniform(rng, 0.05, 0.4);
        c.drift_phase[k] = uniform(rng, 0.0, 2.0 * kPi);
    }
    // Colour temperature (red against blue) and tint (green).
    const double warm = uniform(rng, -0.15, 0.15);
    c.white_balance = {1.0 - warm, 1.0 + uniform(rng, -0.04, 0.04), 1.0 + warm};
    c.eye_gain = {1.0 + uniform(rng, -0.04, 0.04), 1.0 + uniform(rng, -0.04, 0.04)};
    c.vignetting = uniform(rng, 0.0, 0.45);
    return c;
}

}  // namespace

double CameraLooks::gain(double t, Eye eye) const
{
    double g = exposure * eye_gain[eye == Eye::Right ? 1 : 0];
    for (int k = 0; k < 2; ++k) g *= 1.0 + drift_amplitude[k] * std::sin(drift_omega[k] * t + drift_phase[k]);
    return g;
}

HandSkin pick_wide_skin(Rng& rng)
{
    const double darkness = uniform(rng, 0.0, 1.0);
    cv::Vec3f palm = palm_tone(darkness);
    // Between pink (more blue and red) and olive (more green, less blue).
    const double olive = uniform(rng, -1.0, 1.0);
    palm[0] *= float(1.0 - 0.07 * olive);
    palm[1] *= float(1.0 + 0.04 * olive);
    palm[2] *= float(uniform(rng, 0.97, 1.03));
    palm[2] = std::min(palm[2], 248.0f);
    palm[1] = std::min(palm[1], 0.93f * palm[2]);  // red above green above blue
    palm[0] = std::min(palm[0], 0.9f * palm[1]);

    HandSkin s;
    s.palm = palm;
    // The back of the hand is darker and browner than the palm, the more so for dark skin.
    const float back = float(0.92 - 0.35 * darkness);
    s.back = {palm[0] * back, palm[1] * back, palm[2] * back * 0.97f};
    s.rim_mm = uniform(rng, 3.0, 7.0);
    s.gradient = uniform(rng, 0.05, 0.16);
    s.blotches = uniform(rng, 0.02, 0.06);
    return s;
}

Looks draw_looks(double noise_sigma, Rng& rng)
{
    Looks l;
    l.shape = pick_hand_shape(rng);
    l.skin = pick_wide_skin(rng);
    l.bare_forearm = uniform(rng, 0, 1) < 0.35;
    const cv::Vec3f shirt =
        uniform(rng, 0, 1) < 0.15 ? skin_like_colour(rng, l.skin.palm, 250, 600) : non_skin_colour(rng, 0.1, 0.9, 0.7);
    l.upper_arm = shirt * 0.9f;
    l.forearm = l.bare_forearm ? 0.5f * (l.skin.back + l.skin.palm) : shirt;
    l.distance_factor = uniform(rng, 0.8, 1.4);
    l.light = cv::normalize(cv::Vec3d(uniform(rng, -0.9, 0.9), uniform(rng, -0.9, 0.1), -uniform(rng, 0.35, 0.9)));
    l.ambient = uniform(rng, 0.2, 0.5);
    l.hand_light = uniform(rng, 0.75, 1.2);
    l.camera = pick_camera(noise_sigma, rng);
    return l;
}

}  // namespace gc::sim
