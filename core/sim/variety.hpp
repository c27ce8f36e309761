// The wide variety: what a seed draws besides the room's layout and the motion, so that the
// scenes span what real cameras see: the hand's proportions and skin, a sleeve or a bare
// forearm, the light, and the camera's noise, blur, exposure, white balance, vignetting and
// compression.
#pragma once

#include "sim/appearance.hpp"
#include "sim/hand_model.hpp"
#include "sim/scene.hpp"

#include <opencv2/core.hpp>

#include <array>

namespace gc::sim {

// The camera of one scene. Gains are per channel (BGR) on the rendered light.
struct CameraLooks {
    double noise_sigma = 0.0;       // grey levels
    double defocus_sigma_px = 0.0;  // Gaussian blur of the whole frame; 0: sharp
    double shutter_s = 0.0;         // exposure time: the hand's motion blur
    int jpeg_quality = 0;           // 0: no compression
    double exposure = 1.0;          // base gain
    std::array<double, 2> drift_amplitude{}, drift_omega{}, drift_phase{};  // slow exposure changes
    cv::Vec3d white_balance{1.0, 1.0, 1.0};
    std::array<double, 2> eye_gain{1.0, 1.0};  // the two cameras never quite agree
    double vignetting = 0.0;                   // brightness lost in the image corners

    // Gain of frame time `t` (seconds) for `eye`, before the white balance.
    double gain(double t, Eye eye) const;
};

struct Looks {
    HandShape shape;
    HandSkin skin;
    bool bare_forearm = false;
    cv::Vec3f forearm;  // the sleeve's colour, or the bare forearm's skin
    cv::Vec3f upper_arm;
    double distance_factor = 1.0;     // of the hand from the head, on SceneConfig::hand_distance_mm
    cv::Vec3d light{0.0, 0.0, -1.0};  // unit, towards the key light (head frame)
    double ambient = 0.35;
    double hand_light = 1.0;  // the hand in the light (> 1) or in shade (< 1)
    CameraLooks camera;
};

// Proportions of a hand: palm size and shape, finger lengths and widths, the thumb's pose,
// how the other fingers are curled, the wrist.
HandShape pick_hand_shape(Rng& rng);

// A skin tone from very fair to very dark with the palm lighter than the back (more so for
// darker skin) and a seeded hue between pink and olive; BGR under white light.
HandSkin pick_wide_skin(Rng& rng);

// Everything the wide variety draws for one scene; `noise_sigma` is the configured sensor
// noise that the seed scales.
Looks draw_looks(double noise_sigma, Rng& rng);

}  // namespace gc::sim
